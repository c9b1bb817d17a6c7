"""Engineering outputs: the exact sine-loaded strip (pdverify/exact/strip.py), through-section
stresses at stations from fem-plane-stress and pd-higher-order (Eq. 6a-c), support reactions, and what
``pdverify solve`` writes."""

import json

import numpy as np
import pytest
from helpers import ROOT, cli

from pdverify.core.errors import InputError
from pdverify.core.scene_file import load_scene
from pdverify.exact.strip import sine_loaded_strip
from pdverify.registry import run

STRIP = load_scene(ROOT / "studies/examples/sine_strip.toml")
COMPONENTS = ("sigma_xx", "tau_xz", "sigma_zz")


def _exact(scene, x, z):
    s, m = scene.section, scene.material
    return sine_loaded_strip(x, z, scene.length, s.height, m.E, m.poissons_ratio, scene.loads[0].value / s.width)


def _errors(scene, result) -> list[dict]:
    """Per station: max |model - exact| over the section / max |exact| of that component over the whole strip."""
    h = scene.section.height
    X, Z = np.meshgrid(np.linspace(0, scene.length, 201), np.linspace(-h / 2, h / 2, 41))
    whole = _exact(scene, X, Z)
    out = []
    for sec in result.info["sections"]:
        ex = _exact(scene, sec["x"], np.array(sec["z"]))
        out.append({c: np.abs(np.array(sec[c]) - ex[c]).max() / np.abs(whole[c]).max() for c in COMPONENTS})
    return out


# -- the exact solution -------------------------------------------------------------------------


def test_strip_face_conditions_and_compatibility():
    """sigma_zz = p on the top face, 0 on the bottom, no shear on either; the strains of (u, w) by central
    differences are those of the stresses (plane stress) to the differences' error (measured 6e-11 .. 2e-10)."""
    L, h, E, nu, p0 = 1.0, 0.2, 200e9, 0.3, -2e4
    x = np.linspace(0, L, 9)
    top, bot = (sine_loaded_strip(x, z, L, h, E, nu, p0) for z in (h / 2, -h / 2))
    assert np.allclose(top["sigma_zz"], p0 * np.sin(np.pi * x / L), rtol=0, atol=1e-12 * abs(p0))
    for r, c in ((top, "tau_xz"), (bot, "tau_xz"), (bot, "sigma_zz")):
        assert np.abs(r[c]).max() <= 1e-12 * abs(p0)
    X, Z = np.meshgrid(np.linspace(0.1, 0.9, 5), np.linspace(-0.09, 0.09, 5))
    d = 1e-6

    def f(dx, dz):
        return sine_loaded_strip(X + dx, Z + dz, L, h, E, nu, p0)

    s = f(0, 0)
    exx = (f(d, 0)["u"] - f(-d, 0)["u"]) / (2 * d)
    ezz = (f(0, d)["w"] - f(0, -d)["w"]) / (2 * d)
    gam = (f(0, d)["u"] - f(0, -d)["u"] + f(d, 0)["w"] - f(-d, 0)["w"]) / (2 * d)
    scale = np.abs(s["sigma_xx"]).max() / E
    assert np.abs(exx - (s["sigma_xx"] - nu * s["sigma_zz"]) / E).max() < 1e-9 * scale
    assert np.abs(ezz - (s["sigma_zz"] - nu * s["sigma_xx"]) / E).max() < 1e-9 * scale
    assert np.abs(gam - 2 * (1 + nu) * s["tau_xz"] / E).max() < 1e-9 * scale


@pytest.mark.parametrize(("slenderness", "tol"), [(5, 0.03), (50, 3e-4)])
def test_strip_tends_to_beam_theory(slenderness, tol):
    """Top fibre stress at midspan vs M c / I (M = p0 L^2 / pi^2 per unit width): measured +1.44 % at L/h = 5,
    +0.013 % at 50; the 2D correction ~ (h/L)^2."""
    L, E, nu, p0 = 1.0, 200e9, 0.3, -1e4
    h = L / slenderness
    s = sine_loaded_strip(L / 2, h / 2, L, h, E, nu, p0)["sigma_xx"]
    beam = p0 * L**2 / np.pi**2 * (h / 2) / (h**3 / 12)
    assert 0 < s / beam - 1 < tol


# -- through-section stresses --------------------------------------------------------------------


@pytest.mark.slow
def test_q8_stresses_through_the_section_match_the_exact_strip():
    """q8 201 x 32 at x = L/4 and L/2 (L/h = 5), 129 points through the depth (element edges included), error over
    the section / the component's peak over the strip. Measured: sigma_xx 3.3e-5 / 3.9e-5, tau_xz 5.7e-4 / 9.4e-6,
    sigma_zz 6.9e-4 / 9.4e-4 (201 x 16: 6.5e-5, 1.9e-3, 2.4e-3; 401 x 32: 1.7e-5, 4.7e-4, 6.2e-4)."""
    r = run(STRIP, "fem-plane-stress", element="q8", points=201, layers=32, stations="0.25,0.5")
    assert [s["x"] for s in r.info["sections"]] == [0.25, 0.5] and len(r.info["sections"][0]["z"]) == 129
    for e in _errors(STRIP, r):
        assert e["sigma_xx"] < 2e-4 and e["tau_xz"] < 1e-3 and e["sigma_zz"] < 2e-3, e


@pytest.mark.parametrize(("slenderness", "tol"), [(5, 1e-2), (20, 1e-3)])
def test_higher_order_pd_stresses_eq6_against_the_exact_strip(slenderness, tol):
    """pd-higher-order (corrected, 1001 points), Eq. 6a/6c at x = L/4 and L/2. Measured (sigma_xx, tau_xz):
    L/h = 5: 3.1e-3, 3.4e-3 / 4.4e-3, 5e-14; L/h = 20: 1.6e-4, 2.8e-4 / 2.2e-4, 1e-12 (the theory's distance
    from 2D elasticity, ~ (h/L)^2). sigma_zz (Eq. 6b) is odd in z and misses the load's even part: 0.48-0.68."""
    sc = STRIP.with_slenderness(slenderness)
    r = run(sc, "pd-higher-order", points=1001, stations="0.25,0.5")
    for e in _errors(sc, r):
        assert e["sigma_xx"] < tol and e["tau_xz"] < tol, e
        assert 0.3 < e["sigma_zz"] < 1.0, e


@pytest.mark.parametrize("value", ["0.5,abc", "1.5", "-0.1"])
def test_bad_stations_are_one_input_error(value):
    with pytest.raises(InputError, match="stations"):
        run(STRIP, "pd-higher-order", points=51, stations=value)


def test_solve_writes_the_sections_and_reactions(tmp_path, capsys):
    out = tmp_path / "r.json"
    code, _, err = cli(
        [
            "solve",
            ROOT / "studies/examples/sine_strip.toml",
            "-m",
            "pd-higher-order",
            "-o",
            "stations=0.5",
            "--out",
            out,
        ],
        capsys,
    )
    assert code == 0, err
    info = json.loads(out.read_text())["info"]
    assert info["sections"][0]["x"] == 0.5 and len(info["sections"][0]["sigma_xx"]) == 33
    assert abs(info["reactions"]["force_left"] - 100 / np.pi) < 1e-9 * 100  # q0 L / pi each side


# -- reactions -----------------------------------------------------------------------------------

NAMES = ["ss_uniform", "ss_centre_force", "cc_uniform", "cantilever_tip_force", "cantilever_tip_moment"]


@pytest.mark.parametrize("name", NAMES)
def test_reactions_of_pd_higher_order_and_plane_stress_against_exact_timoshenko(name):
    """Yang's five benchmarks (L/h = 5): K u - b at the held DOFs. Statically determinate: the exact reactions to
    round-off (measured <= 2e-12 of the load); clamped-clamped end moments (the theories differ there): exact
    Timoshenko 8.333, pd-higher-order 8.212 (-1.45 %), q8 101 x 8 8.236 (-1.16 %)."""
    sc = load_scene(ROOT / f"studies/paper_yang/{name}.toml")
    ex = run(sc, "exact-timoshenko", points=11).info["reactions"]
    scale = max(abs(v) for v in ex.values())
    for model, opts in (("pd-higher-order", {"points": 201}), ("fem-plane-stress", {"element": "q8", "layers": 8})):
        r = run(sc, model, **opts).info["reactions"]
        for k, v in ex.items():
            tol = 0.02 * scale if name == "cc_uniform" and k.startswith("moment") else 1e-9 * scale
            assert abs(r[k] - v) < tol, (model, k, r[k], v)


@pytest.mark.parametrize("model", ["pd-eb", "fem-eb", "pd-bond-pair", "pd-timoshenko", "fem-timoshenko"])
@pytest.mark.parametrize("name", ["cantilever_tip_force", "ss_centre_force", "cc_uniform"])
def test_beam_model_reactions_from_statics_and_end_moments(model, name):
    """pdverify.core.reactions (every straight static beam model without K u - b): determinate supports from statics
    (exact to round-off); clamped-clamped from the model's end moment (at 201 points, cc uniform, moment_left vs
    8.3333: pd-timoshenko 8.3325, pd-eb 8.3341 (its own moment, second order), pd-bond-pair 8.1464: the one-sided
    second difference of a PD deflection at the clamp, first order). fem-eb and fem-timoshenko give K u - F on their
    held DOFs: exact everywhere."""
    sc = load_scene(ROOT / f"studies/paper_yang/{name}.toml")
    ex = run(sc, "exact-eb", points=11).info["reactions"]
    r = run(sc, model, points=201).info["reactions"]
    scale = max(abs(v) for v in ex.values())
    differences = 1e-2 * scale if model in ("pd-eb", "pd-bond-pair") else 1e-4 * scale  # the clamp's moment
    fem = model.startswith("fem-")
    for k, v in ex.items():
        tol = differences if name == "cc_uniform" and k.startswith("moment") and not fem else 1e-10 * scale
        assert abs(r[k] - v) <= tol, (k, r[k], v)
    if fem:
        assert "K u - F" in r["method"]
    else:
        assert ("statics with" in r["method"] or "the model's own values" in r["method"]) == (name == "cc_uniform")


@pytest.mark.parametrize(("element", "cell", "nodes"), [("q4", "quad", 4), ("q8", "quad8", 8), ("q9", "quad9", 9)])
def test_vtu_quadratic_cells_and_nodal_stresses(element, cell, nodes, tmp_path):
    """The VTU keeps the element's nodes (quad8: mid-sides, quad9: + centre) and carries sigma_xx, sigma_zz, tau_xz,
    von Mises as nodal fields (element gradients at the nodes, averaged). Sine strip, 100 x 16, nodes with
    0.2 L <= x <= 0.8 L (away from the end tractions, which differ from the exact solution's): error / peak,
    measured q8 / q9: sigma_xx 1.5e-4, tau_xz 2.6e-3; q4: 4.6e-3, 8.9e-2 (the mid-side nodes' displacement is the
    solution's own: at most 4.3e-5 of the peak from the exact w, all nodes)."""
    import meshio

    r = run(STRIP, "fem-plane-stress", element=element, points=101, layers=16)
    r.writers[".vtu"](str(tmp_path / "r.vtu"))
    m = meshio.read(tmp_path / "r.vtu")
    assert list(m.cells_dict) == [cell] and m.cells_dict[cell].shape == (100 * 16, nodes)
    P = m.points
    ex = _exact(STRIP, P[:, 0], P[:, 1])
    inner = (P[:, 0] >= 0.2) & (P[:, 0] <= 0.8)
    err = {c: np.abs(m.point_data[c] - ex[c])[inner].max() / np.abs(ex[c]).max() for c in ("sigma_xx", "tau_xz")}
    tol = (2e-2, 0.2) if element == "q4" else (1e-3, 1e-2)
    assert err["sigma_xx"] < tol[0] and err["tau_xz"] < tol[1], err
    assert np.all(m.point_data["von_mises"] >= 0)
    if element != "q4":
        assert np.abs(m.point_data["displacement"][:, 1] - ex["w"]).max() < 1e-4 * np.abs(ex["w"]).max()


def test_solve_csv_and_table_carry_the_sections_as_comment_lines(tmp_path, capsys):
    import pandas as pd

    scene = ROOT / "studies/examples/sine_strip.toml"
    out = tmp_path / "r.csv"
    args = ["solve", scene, "-m", "pd-higher-order", "--points", "51", "-o", "stations=0.25,0.5"]
    assert cli([*args, "--out", out], capsys)[0] == 0
    text = out.read_text().splitlines()
    first = next(line for line in text if not line.startswith("# warning: "))  # the warnings come first
    assert "# section x = 0.25: z, sigma_xx, sigma_zz, tau_xz" in text and first.startswith("# reactions: ")
    assert pd.read_csv(out, comment="#").shape == (51, 8)  # x, w, rotation, theta, theta_star, w_star, M, V
    code, table, _ = cli(args, capsys)
    assert code == 0 and "# section x = 0.5: z, sigma_xx, sigma_zz, tau_xz" in table
