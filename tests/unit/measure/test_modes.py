"""Natural frequencies: the analytic Timoshenko frequencies (pdverify.exact.vibration), the
discrete operators' modes against them under refinement for every support pair, and `pdverify modes`."""

import json
import re

import numpy as np
import pytest
from helpers import PAIRS, ROOT, cli, scene_dict

from pdverify.core.errors import InputError
from pdverify.core.scene_file import parse_scene
from pdverify.exact.vibration import TimoshenkoBeam, beam_end, rod_frequencies
from pdverify.measure.modes import modes

MATERIAL = {"youngs_modulus": 70e9, "poissons_ratio": 0.33, "density": 2700.0}


def _beam(slenderness, left, right, length=2.0):
    h = length / slenderness
    E, G, rho, k = 70e9, 70e9 / 2.66, 2700.0, 5 / 6
    A, Inertia = 0.05 * h, 0.05 * h**3 / 12
    return TimoshenkoBeam(E * Inertia, k * G * A, rho * A, rho * Inertia, length, beam_end(left), beam_end(right))


@pytest.mark.parametrize("slenderness, count", [(4, 8), (20, 8), (100, 8), (20, 600), (4, 600)])
def test_pinned_pinned_determinant_roots_are_the_closed_form(slenderness, count):
    """Pinned–pinned has w = sin(kπx/L), γ = C cos(kπx/L): with λ = kπ/L, (kGA λ² - ρAω²)(EI λ² + kGA - ρIω²)
    = kGA² λ², a quadratic in ω² per k (both spectra), and k = 0 gives the cut-off ω² = kGA/ρI (w = 0,
    γ = const). The determinant's roots are these to 6.2e-14 (measured, L/h = 100; 4.4e-16 at 4); at
    L/h = 4 the first 8 modes reach 1.23 x the cut-off, so the second spectrum and the cut-off mode are in.
    600 modes (the modal transient's sums) cross the two spectra many times, with pairs 0.7 % of the usual
    spacing apart: none is missed (the former scan in z alone lost roots beyond ~250 modes)."""
    b = _beam(slenderness, "pinned", "pinned")
    EI, kGA, rA, rI, L = b.EI, b.kGA, b.rA, b.rI, b.L
    lam2 = (np.arange(1, count + 2) * np.pi / L) ** 2
    a, bb, c = rA * rI, -(rA * (EI * lam2 + kGA) + rI * kGA * lam2), kGA * lam2 * (EI * lam2 + kGA) - kGA**2 * lam2
    disc = np.sqrt(bb * bb - 4 * a * c)
    ref = np.sort(np.concatenate([[kGA / rI], (-bb + disc) / (2 * a), 2 * c / (-bb + disc)]))[:count] ** 0.5
    got = b.frequencies(count)
    assert np.abs(got / ref - 1).max() < 5e-13
    if slenderness == 4:
        assert got[-1] > b.cutoff


# Euler–Bernoulli βL of the first three modes (Blevins, Formulas for natural frequency and mode shape, Table 8-1;
# guided = "sliding"): the Timoshenko frequencies tend to them as (h/L)²
EULER_BERNOULLI = {
    ("clamped", "clamped"): [4.73004074, 7.85320462, 10.9956078],
    ("clamped", "pinned"): [3.92660231, 7.06858275, 10.2101761],
    ("clamped", "free"): [1.87510407, 4.69409113, 7.85475744],
    ("clamped", "guided"): [2.36502037, 5.49780392, 8.63937983],
    ("pinned", "pinned"): [np.pi, 2 * np.pi, 3 * np.pi],
    ("pinned", "guided"): [np.pi / 2, 3 * np.pi / 2, 5 * np.pi / 2],
}


@pytest.mark.parametrize("left,right", PAIRS)
def test_timoshenko_frequencies_tend_to_euler_bernoulli(left, right):
    """Every support pair (and its mirror): βL = L (ρAω²/EI)^¼ of the determinant's roots against Euler–
    Bernoulli's; the difference is the shear and rotary-inertia correction, O((h/L)²): measured 5.4e-6 to
    1.45e-5 at L/h = 1e3 and 100x less at 1e4 (ratios 99.9-100.2)."""
    z_eb = np.array(EULER_BERNOULLI.get((left, right)) or EULER_BERNOULLI[(right, left)])
    diff = []
    for slenderness in (1e3, 1e4):
        b = _beam(slenderness, left, right)
        z = b.L * (b.rA * b.frequencies(3) ** 2 / b.EI) ** 0.25
        assert np.all(z < z_eb)  # shear and rotary inertia lower every frequency
        diff.append(np.abs(z / z_eb - 1).max())
    assert 4e-6 < diff[0] < 2e-5
    assert diff[0] / diff[1] == pytest.approx(100, rel=0.05)  # Blevins' 9 digits leave ~2 % on diff[1]


def test_rod_frequencies_closed_form():
    assert rod_frequencies(2.0, 5000.0, (True, True), 3) == pytest.approx(np.pi * 5000 / 2 * np.array([1, 2, 3]))
    assert rod_frequencies(2.0, 5000.0, (False, True), 2) == pytest.approx(np.pi * 5000 / 2 * np.array([0.5, 1.5]))


def _orders(model, left, right, points, horizon=3):
    sc = parse_scene(scene_dict(left, right, [], material=MATERIAL))
    err = np.array([np.abs(modes(sc, model, {"points": n, "horizon": horizon}, 3).omega) for n in points])
    analytic = modes(sc, model, {"points": points[0], "horizon": horizon}, 3).analytic
    err = np.abs(err / analytic - 1)
    return err, np.log2(err[:-1] / err[1:])


@pytest.mark.parametrize("left,right", PAIRS)
def test_rod_modes_converge_at_order_two(left, right):
    """pd-rod (corrected, m = 3), first three modes, 41 / 81 / 161 / 321 points (δ = 3 dx shrinks with dx): the
    PD sum is a second-order difference (Eq. 19), so order 2. Measured 1.99-2.00 for every pair; errors at
    321 points 5.0e-6 (mode 1, a free end) to 1.8e-4 (mode 3)."""
    err, rate = _orders("pd-rod", left, right, (41, 81, 161, 321))
    assert np.all(np.abs(rate - 2) < 0.3), rate
    assert err[-1].max() < 1e-3


@pytest.mark.parametrize("left,right", PAIRS)
def test_timoshenko_modes_converge_at_order_two(left, right):
    """pd-timoshenko (corrected, m = 3, L/h = 20), first three modes against the determinant's roots, 41 / 81 /
    161 / 321 points: measured orders 1.91-2.00 (every pair; the lowest at the coarse grids of a free or
    guided end); errors at 321 points 3.4e-6 (mode 1, clamped-free) to 3.6e-4 (mode 3, clamped-clamped)."""
    err, rate = _orders("pd-timoshenko", left, right, (41, 81, 161, 321))
    assert np.all(np.abs(rate - 2) < 0.3), rate
    assert err[-1].max() < 1e-3


def test_mirror_scenes_have_the_same_modes():
    """clamped-free and free-clamped: the same spectrum up to the round-off estimate."""
    a, b = (
        modes(parse_scene(scene_dict(left, right, [], material=MATERIAL)), "pd-timoshenko", {"points": 61}, 4)
        for left, right in (("clamped", "free"), ("free", "clamped"))
    )
    assert np.all(np.abs(a.omega / b.omega - 1) <= 10 * a.roundoff)


BEAM_MODELS = ("pd-eb", "pd-bond-pair", "pd-timoshenko", "pd-higher-order", "fem-timoshenko")


@pytest.mark.parametrize("model", BEAM_MODELS)
@pytest.mark.parametrize("length, modulus", [(1e3, 1e5 / 70), (1e-3, 1.0), (1e-6, 1e15)])
def test_modes_of_a_scaled_beam_scale_as_sqrt_of_e_over_length(model, length, modulus):
    """Every length times ``length`` and E times ``modulus``: omega L / sqrt(E) is the same within the modes' own
    round-off estimates, and so are the estimates and the warnings. Before, M^-1 K mixed rows of deflections and
    rotations, whose ratio is the length unit squared: pd-higher-order's modes at L x 1e-3 were [0, 1081, 1081, ...]
    and fem-timoshenko's mode 1 at L x 1e-6 was 0."""

    def table(k, e):
        scene = scene_dict(
            "clamped",
            "free",
            [],
            beam={"length": 2.0 * k},
            section={"width": 0.05 * k, "height": 0.1 * k},
            material=dict(MATERIAL, youngs_modulus=70e9 * e),
        )
        return modes(parse_scene(scene), model, {"points": 41}, 6)

    a, b = table(1.0, 1.0), table(length, modulus)
    scaled = b.omega * length / np.sqrt(modulus)
    assert np.all(np.abs(scaled / a.omega - 1) <= 10 * (a.roundoff + b.roundoff)), scaled / a.omega - 1
    np.testing.assert_allclose(b.roundoff, a.roundoff, rtol=1e-6)
    assert b.warnings == a.warnings


@pytest.mark.parametrize("model", ["pd-timoshenko", "pd-rod", "pd-torsion"])
@pytest.mark.parametrize("left, right", [("pinned", "guided"), ("guided", "pinned"), ("clamped", "guided")])
def test_the_paper_variants_warnings_do_not_depend_on_the_units(model, left, right):
    """The paper variants' closures leave a mode of zero energy, whose computed eigenvalue (1e-14 to 2e-14 of
    ||D K D||) took either sign with the scene's units: "not real positive" came and went (pd-torsion pinned-guided at
    L x 1e6, E x 1e-3: -3.2e-19). Below 1e-12 ||D K D|| an eigenvalue is zero to round-off, whatever its sign. The
    rod's and the bar's paper variant refuse a guided end (no traction condition: Section 4), in every unit."""

    def table(k, e):
        scene = scene_dict(
            left,
            right,
            [],
            beam={"length": 2.0 * k},
            section={"width": 0.05 * k, "height": 0.1 * k},
            material=dict(MATERIAL, youngs_modulus=70e9 * e),
        )
        return modes(parse_scene(scene), model, {"points": 41, "variant": "paper"}, 6)

    if model != "pd-timoshenko":
        for k, e in ((1.0, 1.0), (1e6, 1e-3), (1e-6, 1e15)):
            with pytest.raises(
                InputError, match="guided: variant paper sets no traction condition at an end that does not hold"
            ):
                table(k, e)
        return
    words = lambda t: [re.sub(r"[-+]?\d[\d.]*(e[-+]?\d+)?", "#", w) for w in t.warnings]  # noqa: E731
    base = words(table(1.0, 1.0))
    for k, e in ((1e6, 1e-3), (1e3, 1e5 / 70), (1e-6, 1e15)):
        assert words(table(k, e)) == base, (k, e)


# -- the command ------------------------------------------------------------------------------------


@pytest.fixture
def scene_file(tmp_path):
    def write(density=True, left="clamped", right="free"):
        mat = "density = 2700\n" if density else ""
        text = (
            'name = "modes"\n[beam]\nlength = 2.0\n[section]\nwidth = 0.05\nheight = 0.1\n'
            f"[material]\nyoungs_modulus = 70e9\npoissons_ratio = 0.33\n{mat}"
            f'[supports]\nleft = "{left}"\nright = "{right}"\n'
        )
        path = tmp_path / f"s_{density}_{left}_{right}.toml"
        path.write_text(text)
        return path

    return write


def test_modes_command_prints_frequencies_and_errors(scene_file, capsys):
    """Table, CSV and JSON carry the same numbers: the model's frequencies, the analytic ones and their
    relative error, which equals modes() from Python."""
    path = scene_file()
    ref = modes(parse_scene(scene_dict("clamped", "free", [], material=MATERIAL)), "pd-rod", {"points": 41}, 3)
    code, out, err = cli(["modes", path, "--model", "pd-rod", "-o", "points=41", "--count", "3"], capsys)
    assert code == 0 and "reference: rod clamped-free" in out
    rows = [line.split() for line in out.splitlines() if not line.startswith("#")]
    assert rows[0] == ["mode", "frequency_hz", "analytic_hz", "rel_error", "nonlocal", "roundoff"] and len(rows) == 4
    assert [float(r[3]) for r in rows[1:]] == pytest.approx(ref.columns()["rel_error"], rel=1e-7)
    code, out, _ = cli(
        ["modes", path, "--model", "pd-rod", "-o", "points=41", "--count", "3", "--format", "csv"], capsys
    )
    data = np.genfromtxt([line for line in out.splitlines() if not line.startswith("#")], delimiter=",", names=True)
    assert code == 0 and data["analytic_hz"] == pytest.approx(ref.analytic / (2 * np.pi), rel=1e-11)
    code, out, _ = cli(["modes", path, "--model", "pd-timoshenko", "--count", "2", "--format", "json"], capsys)
    doc = json.loads(out)
    assert code == 0 and doc["model"] == "pd-timoshenko" and len(doc["modes"]) == 2
    assert abs(doc["modes"][0]["rel_error"]) < 1e-3  # measured 3.4e-5 (101 points, m = 3)


@pytest.mark.parametrize(
    "args,message",
    [
        (["--model", "fem-eb"], "model fem-eb: gives no mass and stiffness operator"),
        (["--model", "pd-rod", "--count", "0"], "--count 0: give a number of modes"),
        (["--model", "pd-rod", "-o", "points=11", "--count", "30"], "--count 30: the operator has 10 free DOFs"),
        (["--model", "pd-rod", "-o", "spacing=0.3"], "spacing = 0.3: does not divide the length"),
        (["--model", "pd-rod", "-o", "horizont=2"], "horizont: model pd-rod takes no option"),
        (["--model", "no-such-model"], "model = 'no-such-model': unknown model"),
    ],
)
def test_modes_bad_input_is_one_line(scene_file, capsys, args, message):
    code, out, err = cli(["modes", scene_file(), *args], capsys)
    assert code == 2 and out == "" and err.count("\n") == 1 and err.startswith(f"error: {message}")


def test_modes_needs_density_and_a_held_rod(scene_file, capsys):
    code, _, err = cli(["modes", scene_file(density=False), "--model", "pd-timoshenko"], capsys)
    assert code == 2 and err == "error: material.density: needed for natural frequencies; add density to the scene\n"
    code, _, err = cli(["modes", scene_file(left="guided", right="clamped"), "--model", "pd-rod"], capsys)
    assert code == 0  # guided slides axially; clamped holds
    code, _, err = cli(["modes", scene_file(left="guided", right="free"), "--model", "pd-timoshenko"], capsys)
    assert code == 2 and "supports = guided-free: a mechanism" in err and err.count("\n") == 1
    code, _, err = cli(["modes", scene_file(left="roller", right="roller"), "--model", "pd-rod"], capsys)
    assert code == 2 and "roller-roller: neither end holds the axial displacement" in err and err.count("\n") == 1


@pytest.mark.parametrize(
    "model, options, order",
    [("pd-bond-pair", {"ends": "mirror"}, 2.0), ("pd-eb", {}, 1.0)],
)
def test_the_nonlocal_column_is_the_continuum_at_a_fixed_horizon(model, options, order):
    """Pinned-pinned: the sine modes are the operator's eigenfunctions, so the symbol's shift is the continuum's
    frequency at the horizon. At a fixed delta what remains (rel_error - nonlocal) is the grid's: it falls with dx at
    the model's m-order (the bond pairs' mirror ends: 2; pd-eb's corrected calibration of the discrete sums: 1)."""
    sc = parse_scene(scene_dict("pinned", "pinned", material=MATERIAL))
    rest = []
    for points in (201, 401, 801):
        t = modes(sc, model, {"points": points, "horizon_length": 0.06, **options}, 5)
        c = t.columns()
        assert t.horizon == 0.06 and np.all(c["nonlocal"] < 0)
        rest.append(np.abs(c["rel_error"] - c["nonlocal"]))
    slopes = np.log2(rest[1] / rest[2])
    assert np.all(np.abs(slopes - order) < 0.1), slopes
    assert np.all(rest[2] < 0.1 * np.abs(c["nonlocal"])), (rest[2], c["nonlocal"])


def test_the_nonlocal_column_is_shown_in_every_format(capsys):
    """`pdverify modes` prints the column and the note on what it is in the table, CSV and JSON."""
    path = ROOT / "studies/examples/cantilever_tip_load.toml"
    table = cli(["modes", path, "-m", "pd-eb", "--points", "41"], capsys)[1]
    assert "nonlocal" in table.splitlines()[4] and "# nonlocal: the shift of the model's continuum" in table
    doc = json.loads(cli(["modes", path, "-m", "pd-eb", "--points", "41", "--format", "json"], capsys)[1])
    assert "nonlocal" in doc["modes"][0] and doc["notes"][0].startswith("nonlocal:")
    csv = cli(["modes", path, "-m", "pd-eb", "--points", "41", "--format", "csv"], capsys)[1]
    assert csv.startswith("# nonlocal:") and "nonlocal" in csv.splitlines()[1]
    timoshenko = cli(["modes", path, "-m", "pd-timoshenko", "--points", "41"], capsys)[1]
    assert "nonlocal" not in timoshenko  # no symbol known for its two fields: no column


@pytest.mark.parametrize(
    "change, field",
    [
        ({"supports": {"left": "clamped", "right": "pinned", "inner": [{"position": 0.8, "type": "pinned"}]}}, "inner"),
        ({"supports": {"left": "clamped", "right": {"type": "spring", "stiffness": 1e5}}}, "spring"),
        ({"segments": [{"start": 0.0, "end": 2.0, "section": {"width": 0.05, "height": 0.1}}]}, "segments"),
    ],
    ids=["inner", "spring", "segments"],
)
def test_modes_refuses_a_beam_the_analytic_frequencies_do_not_describe(change, field):
    """The analytic frequencies are those of a uniform beam held at its ends by named supports: fem-timoshenko,
    which solves these statically, gave a table against them (the inner pin's first mode "127 % off"); now one
    line naming what to drop."""
    d = scene_dict("clamped", "pinned", [], material=MATERIAL)
    d.update(change)
    with pytest.raises(InputError, match=field) as exc:
        modes(parse_scene(d), "fem-timoshenko", {"points": 41}, 4)
    assert "uniform beam held at its ends" in exc.value.lines[0]


@pytest.mark.parametrize("model", ["pd-bond-pair", "pd-eb", "fem-timoshenko"])
def test_modes_of_a_beam_with_a_yield_stress_are_the_elastic_beam_s(model):
    """The free vibration of the unloaded beam is elastic: a yield stress and a load path play no part (pd-bond-pair
    refused such a scene as "u and w couple at rest", pd-eb as "elastic only"); the table says what it left out and
    gives the elastic beam's frequencies to the bit."""
    d = scene_dict("clamped", "pinned", [], material=MATERIAL)
    plain = modes(parse_scene(d), model, {"points": 41}, 3)
    d["material"] = dict(MATERIAL, yield_stress=250e6)
    d["loading"] = {"factors": [0.0, 1.0, 0.0], "steps": 4}
    plastic = modes(parse_scene(d), model, {"points": 41}, 3)
    assert np.array_equal(plastic.eigenvalues, plain.eigenvalues)
    assert plastic.notes[0].startswith("yield_stress, [loading]: not part of the free vibration")


def test_a_torsion_bar_of_an_i_section_vibrates_with_its_polar_moment():
    """pd-torsion's dynamics took only a rectangle's polar moment (an I-section was refused): the I's is
    I + 2 t_f b_f³ / 12 + (h - 2 t_f) t_w³ / 12 (its plates' own second moments about the web), and a clamped-free
    bar's frequencies are (2n - 1) π / (2 L) sqrt(G J / (ρ I_p)); the model's first three converge to them at its
    second order (the ratio of the errors at 81 and 161 points near 4)."""
    h, bf, tf, tw = 0.3, 0.15, 0.0107, 0.0071
    section = {"shape": "I", "height": h, "flange_width": bf, "flange_thickness": tf, "web_thickness": tw}
    scene = parse_scene(scene_dict("clamped", "free", [], section=section, material=dict(MATERIAL)))
    polar = scene.section.I + 2 * tf * bf**3 / 12 + (h - 2 * tf) * tw**3 / 12
    assert scene.section.polar == pytest.approx(polar, rel=1e-14)
    c = np.sqrt(scene.material.G * scene.section.J / (MATERIAL["density"] * polar))
    exact = (2 * np.arange(1, 4) - 1) * np.pi / (2 * scene.length) * c
    errors = []
    for points in (81, 161):
        table = modes(scene, "pd-torsion", {"points": points}, 3)
        np.testing.assert_allclose(table.analytic, exact, rtol=1e-12)
        errors.append(np.abs(table.omega / exact - 1).max())
    assert abs(np.log2(errors[0] / errors[1]) - 2) < 0.1, errors


def test_a_singly_symmetric_profile_has_no_polar_moment():
    """A T's twist axis is its shear centre, not its centroid, and twist couples with bending there: not modelled."""
    section = {"shape": "profile", "y": [0.0, 0.2, 0.2, 0.24], "b": [0.02, 0.02, 0.15, 0.15]}
    assert parse_scene(scene_dict("clamped", "free", [], section=section)).section.polar is None


def test_a_true_mode_below_the_zero_line_is_not_called_zero_energy():
    """A slender strip (L/h = 833): its first bending mode lies below 1e-12 ||D K D|| (set by the shear modes), yet is
    the analytic one to 1.1e-6 (fem-timoshenko, 321 points): it carries its round-off warning, not "a mode of zero
    energy" (sweep 12), which the paper variants' closures keep (test above)."""
    d = scene_dict("clamped", "free", [], beam={"length": 1.0}, section={"width": 0.02, "height": 0.0012})
    d["material"] = {"youngs_modulus": 200e9, "poissons_ratio": 0.3, "density": 7850.0}
    t = modes(parse_scene(d), "fem-timoshenko", {"points": 321}, 4)
    assert not any("zero energy" in w for w in t.warnings), t.warnings
    assert any(w.startswith("mode 1: round-off may reach") for w in t.warnings), t.warnings
    assert abs(t.omega[0] / t.analytic[0] - 1) < 1e-5
