"""exact-eb under a prescribed deflection (pdverify/exact/brittle.py): the elastic beam up to the fibre theory's first
failure, then two rigid pieces hinged at the failed section (O'Grady & Foster 2014, Fig. 9's classical beam). Every
value is a textbook closed form: the centre force on a simply supported beam, 48 EI Δ / L³, the tip force on a
cantilever, 3 EI Δ / L³, the failure moment EI ε_f / c."""

import numpy as np
import pytest

from pdverify.core.errors import InputError
from pdverify.core.scene_file import parse_scene
from pdverify.registry import run

E, L, B, H, EF = 200e9, 2.0, 0.1, 0.1, 1e-3
EI = E * B * H**3 / 12
M_F = EI * EF / (H / 2)  # the failure moment: the extreme fibre at failure_strain
BRITTLE = {"failure_strain": EF}


def scene(supports=("pinned", "pinned"), position=L / 2, value=-0.02, steps=30, loads=None, material=None):
    return parse_scene(
        {
            "name": "brittle",
            "beam": {"length": L},
            "section": {"width": B, "height": H},
            "material": {"youngs_modulus": E, "poissons_ratio": 0.3, **(BRITTLE if material is None else material)},
            "supports": {"left": supports[0], "right": supports[1]},
            "loads": loads or [{"type": "displacement", "position": position, "value": value}],
            "loading": {"factors": [0.0, 1.0], "steps": steps},
        }
    )


def test_simply_supported_centre_deflection_is_elastic_to_the_failure_force_then_a_hinge():
    """Fig. 9's beam: the centre force 48 EI Δ / L³ until it reaches 4 M_f / L, then no force and two straight
    halves."""
    r = run(scene(), "exact-eb", points=201)
    lp = r.info["load_path"]
    assert lp["failure_force"] == pytest.approx(4 * M_F / L, rel=1e-12)
    delta_f = 4 * M_F / L * L**3 / (48 * EI)
    assert lp["first_failure_factor"] == pytest.approx(delta_f / 0.02, rel=1e-12)
    x = r.x
    for step in r.path:
        d = -0.02 * step["factor"]
        F = step["reactions"]["force_displacement_0"]
        if not step["broken"]:
            assert F == pytest.approx(48 * EI * d / L**3, rel=1e-12, abs=1e-9)
            xs = np.minimum(x, L - x)  # the centre force's deflection, symmetric
            w = F * xs * (3 * L**2 - 4 * xs**2) / (48 * EI)
            assert np.abs(step["w"] - w).max() <= 1e-12 * 0.02
        else:
            assert F == 0.0 and step["reactions"]["force_left"] == 0.0
            assert np.abs(step["w"] - d * (1 - np.abs(x - L / 2) / (L / 2))).max() <= 1e-14
    broken = [s["broken"] for s in r.path]
    assert broken.index(1) == 11  # 30 steps to 3 Δ_f: step 10 reaches Δ_f itself (still elastic), step 11 passes it
    assert r.fields["health"][100] == 0.0 and r.fields["health"].sum() == 200
    assert np.abs(r.fields["M"]).max() == 0.0


def test_a_cantilever_breaks_at_its_root_and_turns_about_it():
    """Tip deflection Δ: the tip force 3 EI Δ / L³ until its root moment F L reaches M_f, then w = Δ x / L."""
    r = run(scene(("clamped", "free"), position=L, value=-0.2, steps=20), "exact-eb", points=41)
    lp = r.info["load_path"]
    assert lp["peak_position"] == 0.0 and lp["failure_force"] == pytest.approx(M_F / L, rel=1e-12)
    assert lp["first_failure_factor"] == pytest.approx(M_F / L * L**3 / (3 * EI) / 0.2, rel=1e-12)
    assert np.abs(r.w - (-0.2) * r.x / L).max() <= 1e-15
    assert r.info["reactions"]["force_left"] == 0.0


def test_an_off_centre_deflection_hinges_under_itself_and_mirrors():
    """At a = 0.6 L the peak moment is under the deflection: the hinge forms there; the mirror scene (a = 0.4 L)
    gives the mirror image at every step."""
    a = run(scene(position=0.6 * L, steps=12), "exact-eb", points=101)
    b = run(scene(position=0.4 * L, steps=12), "exact-eb", points=101)
    assert a.info["load_path"]["peak_position"] == pytest.approx(0.6 * L, rel=1e-12)
    for sa, sb in zip(a.path, b.path, strict=True):
        assert sa["broken"] == sb["broken"]
        assert np.abs(sa["w"] - sb["w"][::-1]).max() <= 1e-15 + 1e-12 * np.abs(sa["w"]).max()
    assert a.path[-1]["broken"] == 1
    kink = np.diff(a.w, 2)  # straight on each side of the hinge
    assert np.flatnonzero(np.abs(kink) > 1e-12 * 0.02).tolist() == [59]


def test_an_elastic_beam_under_a_prescribed_deflection_never_breaks():
    r = run(scene(material={}, steps=5), "exact-eb", points=21)
    assert r.info["load_path"]["first_failure_factor"] is None
    assert all(s["broken"] == 0 for s in r.path)
    assert r.info["reactions"]["force_displacement_0"] == pytest.approx(48 * EI * -0.02 / L**3, rel=1e-12)


@pytest.mark.parametrize(
    "kwargs, field",
    [
        (
            {
                "loads": [
                    {"type": "displacement", "position": 1.0, "value": -0.01},
                    {"type": "point_force", "position": 0.5, "value": -10.0},
                ]
            },
            "loads",
        ),
        ({"material": {"yield_stress": 250e6}}, "material.yield_stress"),
        ({"supports": ("clamped", "pinned")}, "supports"),
    ],
    ids=["with another load", "with a yield stress", "indeterminate"],
)
def test_what_it_cannot_take_is_one_line(kwargs, field):
    with pytest.raises(InputError) as err:
        run(scene(**kwargs), "exact-eb", points=21)
    assert len(err.value.lines) == 1 and err.value.lines[0].startswith(field), err.value.lines


def test_exact_timoshenko_refuses_a_prescribed_deflection():
    sc = scene(material={}).model_copy(update={"loading": None})
    with pytest.raises(InputError) as err:
        run(sc, "exact-timoshenko", points=21)
    assert "displacement" in err.value.lines[0]


def test_a_scaled_beam_gives_the_same_relative_path():
    """Lengths times s (1e-6, 1e3), the prescribed deflection with them: the same failure factor and the same w / s at
    every step, unloading after the failure included (the hinge stays)."""

    def path(s):
        d = {"factors": [0.0, 1.0, 0.2], "steps": 7}
        sc = parse_scene(
            {
                "name": "scaled",
                "beam": {"length": L * s},
                "section": {"width": B * s, "height": H * s},
                "material": {"youngs_modulus": E, "poissons_ratio": 0.3, **BRITTLE},
                "supports": {"left": "pinned", "right": "roller"},
                "loads": [{"type": "displacement", "position": 0.35 * L * s, "value": -0.02 * s}],
                "loading": d,
            }
        )
        r = run(sc, "exact-eb", points=41)
        return r.info["load_path"]["first_failure_factor"], np.array([p["w"] for p in r.path]) / s, r.path

    f1, w1, p1 = path(1.0)
    assert [p["broken"] for p in p1] == [0] * 3 + [1] * 12
    for s in (1e-6, 1e3):
        fs, ws, _ = path(s)
        assert fs == pytest.approx(f1, rel=1e-14) and np.abs(ws - w1).max() <= 1e-14 * np.abs(w1).max()
