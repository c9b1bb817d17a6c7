"""Dispersion relations (pdverify.numerics.dispersion): the interior stencil's branches against the
continuum, rod and Timoshenko beam, horizons 1-4."""

import numpy as np
import pytest
from helpers import ROOT, scene_dict

from pdverify.core.scene_file import parse_scene
from pdverify.numerics.dispersion import stencil_branches, timoshenko_branches
from pdverify.papers.moyer import operator as O
from pdverify.papers.moyer.kernels import rod_kernel

MATERIAL = {"youngs_modulus": 70e9, "poissons_ratio": 0.33, "density": 2700.0}
SCENE = parse_scene(scene_dict("clamped", "clamped", [], material=MATERIAL))
K = 2 * np.pi / np.array([2.0, 0.5])  # wavelengths L and L/4


@pytest.mark.parametrize("m", [1, 2, 3, 4])
def test_rod_branch_has_the_kernels_dispersion(m):
    """Rod: ω² = B Σ_j c_j 2 (1 - cos jkΔ) / ρ, so ω / ck - 1 = -(kΔ)² Σ c_j j⁴ / (24 Σ c_j j²) + O((kΔ)⁴)
    (m = 3: -0.208 (kΔ)²). Measured within 8.3e-4 of it (relative, the O((kΔ)⁴) rest) at 401 points."""
    d = O.rod_operator(SCENE, 401, m, "corrected")
    dx = d.x[1] - d.x[0]
    got = stencil_branches(d.op.blocks, np.asarray(d.field_mass), K * dx)[:, 0]
    c = np.sqrt(SCENE.EA / (2700.0 * SCENE.section.A))
    cj, j = rod_kernel(m), np.arange(1, m + 1)
    expected = -((K * dx) ** 2) * (cj * j**4).sum() / (24 * (cj * j**2).sum())
    assert got / (c * K) - 1 == pytest.approx(expected, rel=2e-3)


@pytest.mark.parametrize("m", [1, 2, 3, 4])
def test_beam_branches_converge_to_timoshenko_at_order_two(m):
    """Corrected beam stencil, bending and shear branches at wavelengths L and L/4 (L/h = 20), 201 and 401
    points: below the continuum (measured 1.3e-6 .. 1.0e-2 at 201 points, m = 1..4) and 4.0x closer on the
    finer grid (order 2: measured ratios 3.98-4.00)."""
    ex = timoshenko_branches(K, SCENE.EI, SCENE.kGA, 2700.0 * SCENE.section.A, 2700.0 * SCENE.section.I)
    err = []
    for n in (201, 401):
        d = O.beam_operator(SCENE, n, m, "corrected")
        got = stencil_branches(d.op.blocks, np.asarray(d.field_mass), K * (d.x[1] - d.x[0]))
        err.append(got / ex - 1)
    assert np.all(err[0] < 0) and np.all(err[1] < 0)
    assert np.all(np.abs(np.log2(err[0] / err[1]) - 2) < 0.05)


def test_timoshenko_branches_limits():
    """Long waves: the bending branch tends to Euler-Bernoulli's sqrt(EI/ρA) k² and the shear branch to the
    cut-off sqrt(kGA/ρI)."""
    rA, rI = 2700.0 * SCENE.section.A, 2700.0 * SCENE.section.I
    b = timoshenko_branches(np.array([1e-4]), SCENE.EI, SCENE.kGA, rA, rI)[0]
    assert b[0] == pytest.approx(np.sqrt(SCENE.EI / rA) * 1e-8, rel=1e-8)
    assert b[1] == pytest.approx(np.sqrt(SCENE.kGA / rI), rel=1e-8)


@pytest.mark.slow
def test_the_report_draws_each_pd_model_s_dispersion(tmp_path):
    """A study running pd-timoshenko and pd-rod: the report holds one dispersion figure per (model, variant) at
    its finest grid, read from the study's scenes.json (the scenes as run); other models get none. A relation
    depends on the grid, section and material, not on the loads: two rod scenes that differ in their load share
    one figure, which names both (on the index and on the paper's page)."""
    import shutil

    from pdverify import run_study
    from pdverify.report.build import build_report

    for name in ("beam_transient.toml", "rod_transient.toml"):
        shutil.copy(ROOT / "studies" / "paper_moyer" / name, tmp_path / name)
    rod = (tmp_path / "rod_transient.toml").read_text()
    other = rod.replace('name = "rod, sine axial load from rest"', 'name = "rod, a larger load"')
    (tmp_path / "rod2_transient.toml").write_text(other.replace("axial = 3000.0", "axial = 6000.0"))
    runs = [
        ("pd-timoshenko", '["beam_transient.toml"]', "[21, 41]"),
        ("pd-rod", '["rod_transient.toml", "rod2_transient.toml"]', "41"),
        ("fem-timoshenko", '["beam_transient.toml"]', "21"),
    ]
    text = 'name = "waves"\nscenes = ["beam_transient.toml", "rod_transient.toml", "rod2_transient.toml"]\n'
    text += 'reference = "none"\n'
    for model, scenes, points in runs:
        text += f'[[runs]]\nmodel = "{model}"\nscenes = {scenes}\npoints = {points}\n'
    (tmp_path / "s.toml").write_text(text)
    run_study(tmp_path / "s.toml", out=tmp_path / "out", workers=1, progress=False)
    index = build_report(tmp_path / "out").read_text()
    paper = (tmp_path / "out" / "paper-scenes.html").read_text()
    for page in (index, paper):
        assert page.count("pd-timoshenko (energy) dispersion, 41 points") == 1  # the default variant
        assert page.count("pd-rod (corrected) dispersion, 41 points") == 1 and "fem-timoshenko (" not in page
        assert "rod, sine axial load from rest; rod, a larger load" in page
    # the beam's three transient runs overlaid, whole run and early time (Moyer & Miraglia Figs 3, 9, 10), on the
    # paper's page; the rod's one run has none
    assert "w(x=1), every run" in paper and "w(x=1), early time" in paper and "u(x=1), every run" not in paper


@pytest.mark.parametrize("model", ["pd-timoshenko", "pd-rod"])
@pytest.mark.parametrize("variant", ["corrected", "energy"])
def test_a_relation_is_the_same_whatever_holds_the_beam(model, variant):
    """The report's relation is the interior stencil's: a spring end, a support inside the span and a load give the
    clamped beam's branches (the report stopped with exit 70 on a spring end: the static operator has no rows for
    it)."""
    from pdverify.report.waves import dispersion_data

    spring = {"type": "spring", "stiffness": 1e6, "rotational_stiffness": 1e4}
    d = scene_dict("pinned", "clamped", [{"type": "distributed", "value": -100.0}], material=MATERIAL)
    d["supports"] = {"left": "pinned", "right": spring, "inner": [{"position": 0.4, "type": "pinned"}]}
    held = dispersion_data(parse_scene(d), model, 41, variant)
    plain = dispersion_data(SCENE, model, 41, variant)
    assert held is not None and held.key() == plain.key()
