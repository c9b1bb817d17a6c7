"""pd-higher-order at a fixed horizon (docs/nonlocal.md, "A limit at fixed delta?"): with bonds measured along their
path (``shear = path``, the corrected default) at truncated ends, a pinned or guided end or a clamped end held
through its layer spring (``clamp = layer``) has no limit as m grows at fixed delta, and its continuum says so;
a free end, ``clamp = face``, ``shear = centred`` and ``stretch = path`` (with the patch-test end layer) converge."""

import numpy as np
import pytest

from pdverify.core.scene_file import load_scene
from pdverify.registry import get_model, run

DELTA = 0.1
NONLOCAL = "studies/nonlocal"


def changes(member: str, ms, delta: float = DELTA, **opts) -> list[float]:
    """The largest change of w between successive m at fixed delta, at the coarsest grid's points, relative."""
    scene = load_scene(f"{NONLOCAL}/{member}.toml")
    values = []
    for m in ms:
        r = run(scene, "pd-higher-order", points=int(round(m / delta)) + 1, horizon_length=delta, **opts)
        values.append(np.asarray(r.w)[:: m // ms[0]])
    top = np.abs(values[-1]).max()
    return [float(np.abs(b - a).max() / top) for a, b in zip(values, values[1:])]


@pytest.mark.parametrize(
    "member, options, declared",
    [
        ("cc_sine", {}, True),
        ("cf_sine", {}, True),
        ("pp_sine", {}, True),
        ("pg_sine", {}, True),
        ("cc_sine", {"clamp": "face"}, False),
        ("cf_sine", {"clamp": "face"}, False),
        ("pp_sine", {"shear": "centred"}, False),
        ("pp_sine", {"ends": "mirror", "pin": "mid", "loads": "mid"}, False),
        ("pp_sine", {"stretch": "path"}, False),
        ("cc_sine", {"stretch": "path"}, False),
        ("pp_sine", {"stretch": "path", "end_layer": "point"}, True),
        ("pp_sine", {"stretch": "path", "ends": "taylor"}, True),
    ],
)
def test_the_continuum_declares_no_limit_where_the_path_measures_grow(member, options, declared):
    scene = load_scene(f"{NONLOCAL}/{member}.toml")
    model = get_model("pd-higher-order")
    params = model.resolve(scene, dict(options, points=81, horizon_length=DELTA))
    assert (model.continuum_limit(scene, params) is not None) == declared
    c = run(scene, "pd-higher-order", points=81, horizon_length=DELTA, continuum=True, **options)
    assert bool(c.info.get("no_limit")) == declared
    # a solve at that fixed horizon says so in its warnings; the same grid with the horizon tied to it does not
    said = [
        w for w in run(scene, "pd-higher-order", points=81, horizon_length=DELTA, **options).info.get("warnings", [])
    ]
    assert any("horizon_length = 0.1" in w and "do not converge" in w for w in said) == declared, said
    tied = run(scene, "pd-higher-order", points=81, horizon=8, **options).info.get("warnings", [])
    assert not any("do not converge" in w for w in tied), tied


@pytest.mark.parametrize("m, negative", [(3, False), (8, False), (9, True), (16, True)])
def test_negative_end_layer_weights_are_recorded(m, negative):
    """The patch-test end layer's weights at the end point grow like m and some turn negative from m of about 8.5
    (benchmarks/end_layer_weights.py): the result records the least weight over the interior one of its offset."""
    from pdverify.papers.yang.bonds import end_layer_ratios

    scene = load_scene(f"{NONLOCAL}/pp_sine.toml")
    r = run(scene, "pd-higher-order", points=10 * m + 1, horizon=m)
    least = float(end_layer_ratios(10 * m + 1, m, scene.length / (10 * m), "partial").min())
    assert (least < 0) == negative
    assert r.info.get("end_layer_negative_weight") == (least if negative else None)


@pytest.mark.slow
def test_path_measures_at_a_pinned_end_stop_converging_where_centred_ones_converge():
    """delta = 0.2 m on the pinned-pinned sine load, m = 32, 64, 128 (round-off bounds below 1e-9, far below the
    changes): with the path measures the change from 64 to 128 is larger than the one from 32 to 64 (measured 1.5
    times: the sequence has no limit); with the centred measures it is 2.9 times smaller (order 1.52); a clamped face
    with the path measures converges at about first order (clamped-free, m = 8 -> 32: order 1.04), and so does the
    stretch measured along the path too (``stretch = path``: 9.8e-5, 4.0e-5, order 1.30; 1.09 from 128 to 256)."""
    path = changes("pp_sine", (32, 64, 128), delta=0.2)
    centred = changes("pp_sine", (32, 64, 128), delta=0.2, shear="centred")
    face = changes("cf_sine", (8, 16, 32), delta=0.2, clamp="face")
    stretch = changes("pp_sine", (32, 64, 128), delta=0.2, stretch="path")
    assert path[1] > path[0]  # the changes grow
    assert centred[1] <= 0.6 * centred[0]  # order above 0.74
    assert face[1] <= 0.6 * face[0]
    assert stretch[1] <= 0.6 * stretch[0]


def test_the_stretch_along_the_path_needs_the_shear_along_the_path():
    """``stretch = path`` is defined on the path measures (path_measures): with other shear measures, or on the paper
    variant (Eq. 14b), one line naming the option."""
    from pdverify.core.errors import InputError

    scene = load_scene(f"{NONLOCAL}/pp_sine.toml")
    with pytest.raises(InputError, match="shear = path"):
        run(scene, "pd-higher-order", points=41, stretch="path", shear="centred")
    with pytest.raises(InputError, match="stretch"):
        run(scene, "pd-higher-order", points=41, stretch="path", variant="paper")


def test_the_end_layer_weights_at_the_end_point_grow_like_m_at_a_fixed_horizon():
    """``end_layer = patch`` holds every nearest-neighbour segment at the interior's total bond weight. The segment
    next to an end is covered only by the bonds from or onto the end point, two per offset, where an interior segment
    has 2d bonds of offset d, so at a fixed horizon those bonds' weights grow like m (docs/nonlocal.md; measured
    12.5, 24.7, 47.8, 93.4 times the interior weight for the bond from point 1 onto the end at m = 8 ... 64), while a
    bond away from the end point settles (1.35, 1.46, 1.53, 1.56): the order in m of the first is 1, of the second 0."""
    from pdverify.numerics.families import family
    from pdverify.papers.yang.bonds import end_layer_weights

    def ratio(m: int, point: int, offset: int) -> float:
        dx = 0.2 / m
        k, off, w = end_layer_weights(int(round(1.0 / dx)) + 1, float(m), dx, "partial")
        d, beta = family(m, dx, "corrected", "partial")
        r = beta / (d * dx)
        interior = dx * r[abs(offset) - 1] / (2.0 * np.sum(r * (d * dx) ** 2))  # the per-point weight inside
        return float(w[(k == point) & (off == offset)][0] / interior)

    onto_end = [ratio(m, 1, -1) for m in (16, 32, 64)]
    inside = [ratio(m, m // 2, 1) for m in (16, 32, 64)]
    assert np.all(np.abs(np.log2(np.divide(onto_end[1:], onto_end[:-1])) - 1) < 0.1), onto_end
    assert np.all(np.abs(np.log2(np.divide(inside[1:], inside[:-1]))) < 0.1), inside
