"""Point forces and moments anywhere: second order on every path of pd-bond-pair and pd-eb.

A load at (i + t) dx is split between the two nearest points, so the error constant depends on t and the
order read from one fixed position fluctuates from grid to grid (a moment at 0.4219 m: 2.17, 2.10, 1.76 over
101 -> 801 points, Taylor ends, because t runs through 0.10, 0.19, 0.38, 0.76). The error on a grid is taken
here as the largest over positions base + t dx, t in {0.1, 0.5, 0.9}: that error falls as dx² (measured
1.99-2.00 per doubling, 101 -> 1601 points, for the same moment).
"""

import numpy as np
import pytest
from helpers import PAIRS, STUDIES, scene_dict

from pdverify.core.scene import SUPPORTS, is_mechanism
from pdverify.core.scene_file import parse_scene
from pdverify.exact.straight import solve_straight
from pdverify.measure.metrics import ROUND_OFF_LEVEL
from pdverify.registry import get_model, run

L = 2.0  # conftest's beam
ALL_PAIRS = [(l, r) for l in SUPPORTS for r in SUPPORTS if not is_mechanism(l, r)]
LOADS = [
    ("point_force", 0.7037, -300.0),
    ("point_force", 1.8123, -300.0),
    ("point_moment", 1.3011, 150.0),
    ("point_moment", 0.4219, 150.0),
]
T = (0.1, 0.5, 0.9)
# path: (model, options, support pairs). Transverse-only paths take roller = pinned (tests/test_supports.py).
PATHS = {
    "pd-bond-pair taylor mixed": ("pd-bond-pair", {}, PAIRS),
    "pd-bond-pair taylor direct": ("pd-bond-pair", {"form": "direct"}, PAIRS),
    "pd-bond-pair mirror": ("pd-bond-pair", {"ends": "mirror"}, ALL_PAIRS),
    "pd-eb corrected mixed": ("pd-eb", {}, PAIRS),
    "pd-eb corrected direct": ("pd-eb", {"form": "direct"}, PAIRS),
}


def worst_error(name, opts, left, right, kind, base, value, n, bounds=None):
    """Largest max|w - exact| / max|exact| over the positions (floor(base / dx) + t) dx, t in T; the solves' largest
    round-off bound (info error_bound) appended to ``bounds`` when given."""
    dx = L / (n - 1)
    out = 0.0
    for t in T:
        load = {"type": kind, "position": (np.floor(base / dx) + t) * dx, "value": value}
        sc = parse_scene(scene_dict(left, right, [load]))
        r = run(sc, name, points=n, grid_check=False, **opts)  # measured against exact: no estimate asked for
        ex = solve_straight(sc, False).fields(r.x)["w"]
        out = max(out, np.abs(r.w - ex).max() / np.abs(ex).max())
        if bounds is not None:
            bounds.append(r.info["error_bound"])
    return out


@pytest.mark.slow
@pytest.mark.parametrize("path", list(PATHS))
def test_point_loads_anywhere_second_order(path):
    """Measured, 101 -> 201 -> 401 points, every pair and load: order >= 1.98 (Taylor mixed), 1.97 (Taylor
    direct), 1.99 (mirror, rollers included), 1.99 (pd-eb mixed), 1.94 (pd-eb direct). The direct forms
    reach their round-off floor (~1e-6, warned: round-off bound past 1e-6) from 401 points, so they are
    read below it; where a model is exact (pd-eb on a cantilever under a couple) the error is round-off growing
    like N^4 and is judged against each solve's own round-off bound. pd-eb's paper variant does not converge at all
    (docs/models/diyaroglu.md). Moments on the chord (i, i+1) and forces at the nearest point would be first order."""
    name, opts, pairs = PATHS[path]
    low = []
    for left, right in pairs:
        for kind, base, value in LOADS:
            bounds = [[], [], []]
            e = [worst_error(name, opts, left, right, kind, base, value, n, b) for n, b in zip((101, 201, 401), bounds)]
            orders = np.log2(np.array(e[:-1]) / np.array(e[1:]))
            # exact from the second grid on (the error is round-off, within each solve's own bound): no order to fit
            at_round_off = all(ei < ROUND_OFF_LEVEL or ei <= max(b) for ei, b in zip(e[1:], bounds[1:]))
            if orders.min() < 1.8 and not at_round_off:
                low.append((left, right, kind, base, e, orders.round(2).tolist()))
    assert not low


def test_mid_span_moment_off_the_grid_on_the_mirror_path():
    """The fast tier's witness: a moment between two points of a clamped-pinned beam, mirror ends, within
    0.6 % at 101 points and second order (a moment acting on the chord (i, i + 1) instead is 16.6 % off at 101
    points)."""
    e = [
        worst_error("pd-bond-pair", {"ends": "mirror"}, "clamped", "pinned", "point_moment", 1.0, 150.0, n)
        for n in (101, 201)
    ]
    assert e[0] < 6e-3
    assert np.log2(e[0] / e[1]) > 1.8


def nonlinear_tip(left, right, kind, position, value, n):
    sc = parse_scene(scene_dict(left, right, [{"type": kind, "position": position, "value": value}]))
    return run(sc, "pd-bond-pair", points=n, nonlinear=True, ends="mirror", steps=5, grid_check=False)


@pytest.mark.slow
@pytest.mark.parametrize(
    "left,right,kind,value", [("clamped", "free", "point_moment", 4.0e4), ("pinned", "guided", "point_force", -2.0e4)]
)
def test_point_loads_anywhere_second_order_on_the_nonlinear_path(left, right, kind, value):
    """Finite rotations (slopes up to 0.18 / 0.08 rad), the load between two points (t = 0.25, 0.75 of each
    grid's spacing), against the 3201-point solution with the same load: measured orders 2.00, 2.01
    (moment) and 2.01, 2.02 (force) over 101 -> 201 -> 401; on six pairs 1.99-2.03."""
    base = 1.3011 if kind == "point_moment" else 0.7037
    errs = []
    for n in (101, 201, 401):
        dx, e = L / (n - 1), 0.0
        for t in (0.25, 0.75):
            p = (np.floor(base / dx) + t) * dx
            a, ref = nonlinear_tip(left, right, kind, p, value, n), nonlinear_tip(left, right, kind, p, value, 3201)
            s = 3200 // (n - 1)
            d = np.hypot(a.w - ref.w[::s], a.fields["u"] - ref.fields["u"][::s]).max()
            e = max(e, d / np.abs(ref.w).max())
        errs.append(e)
    orders = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert orders.min() > 1.8, (errs, orders)


NARROW = {"type": "distributed", "value": -50.0, "start": 1.65516, "end": 1.65610}  # 0.94 mm wide


@pytest.mark.parametrize("model", ["pd-eb", "pd-bond-pair", "pd-higher-order", "pd-timoshenko"])
def test_a_load_inside_one_cell_is_flagged(model):
    """A partial load narrower than the spacing that lies inside one point's cell acts on that point as a whole
    (pd_common.narrow_load_warnings): at 401 points (cell 1.6525-1.6575) the result says so and is off by more than
    1e-3 (measured 2.9e-3 to 3.2e-3, the same at 801); at 1601 points the load straddles two cells, no warning, and the
    error is small (measured 1.1e-5 to 1.1e-4). A full-span load is never flagged."""
    sc = parse_scene(scene_dict("clamped", "clamped", [NARROW], section={"width": 0.05, "height": 2.0 / 1541}))
    exact = "exact-timoshenko" if model in ("pd-higher-order", "pd-timoshenko") else "exact-eb"
    # pd-eb places a distributed load by its particular moment, exactly at any width (5.6e-5 at 401 points): no flag
    for n, flagged in ((401, model != "pd-eb"), (1601, False)):
        r = run(sc, model, points=n)
        ex = run(sc, exact, points=n).w
        err = np.abs(r.w - ex).max() / np.abs(ex).max()
        said = [w for w in r.info.get("warnings", []) if "inside one point's cell" in w]
        assert bool(said) == flagged and (err > 1e-3) == flagged, (n, err, said)
    whole = parse_scene(scene_dict("clamped", "clamped", [dict(NARROW, start=None, end=None)]))
    assert not any("cell" in w for w in run(whole, model, points=401).info.get("warnings", []))


@pytest.mark.parametrize(
    "name,reference,quantity", [("pd-eb", "exact-eb", "w"), ("pd-timoshenko", "exact-timoshenko", "rotation")]
)
def test_a_couple_on_a_segment_joint_is_first_order_and_warned(name, reference, quantity):
    """A couple on the joint of two segments: the kink that takes it and the change of section meet at one point, and
    pd-eb's deflection (pd-timoshenko's rotation) is first order there, 100 times the error of the same couple 0.1 m
    off the joint; the result says so (it did not)."""
    from pdverify.core.scene_file import load_scene

    sc = load_scene(STUDIES / "examples/couple_at_joint.toml")
    off = sc.model_copy(update={"loads": [sc.loads[0].model_copy(update={"position": 0.9})]})
    errors = []
    for scene in (sc, off):
        r = run(scene, name, points=201)
        exact = get_model(reference).evaluator(scene, {})(r.x)[quantity]
        got = r.w if quantity == "w" else r.rotation
        errors.append(np.abs(got - exact).max() / np.abs(exact).max())
        said = [w for w in r.info.get("warnings", []) if "segment joint" in w]
        assert len(said) == (scene is sc)
    assert errors[0] > 10 * errors[1], errors


def test_a_couple_on_a_segment_joint_gives_the_mirror_image_in_the_mirror_scene():
    """pd-eb's kink of a couple on a joint took the right-hand segment's EI, so the mirror scene (the joint's sides
    swapped) took the other's: 8.9e-4 of max |w| apart at 41 points (sweep 4). Both sides' mean 1 / EI, as in the
    mirror scene: the mirror image to round-off, and as far from exact-eb as before (7.4e-3 against 7.6e-3 and
    7.3e-3)."""
    import tomllib

    from pdverify.core.scene_file import parse_scene
    from pdverify.verify.suite import mirror

    d = tomllib.loads((STUDIES / "examples/couple_at_joint.toml").read_text())
    a, b = (run(parse_scene(sc), "pd-eb", points=41) for sc in (d, mirror(d)))
    assert np.abs(b.w[::-1] - a.w).max() <= 1e-12 * np.abs(a.w).max()


NARROW_MODELS = [
    "pd-eb", "pd-curved", "fem-eb", "fem-timoshenko", "pd-timoshenko", "pd-bond-pair", "pd-higher-order", "exact-eb",
    "exact-curved", "exact-higher-order", "fem-plane-stress",
]  # fmt: skip


@pytest.mark.parametrize("width", [1e-12, 1e-10, 1e-9])
@pytest.mark.parametrize("model", NARROW_MODELS)
def test_a_load_on_a_narrow_span_acts_as_its_resultant(model, width):
    """1 N spread over a span of 1e-12 ... 1e-9 m at 0.7 m of a 2 m cantilever acts as a 1 N force in its middle: the
    two differ by O(width / L) in w. pd-eb and pd-curved rounded such a span's two ends to one point and lost the
    load (w = 0 everywhere, no warning: pd-curved from 1e-9 m down, pd-eb from 1e-11 m), and so did fem-plane-stress
    and exact-curved at 1e-12 m; fem-eb made it an element 1e-12 m long and lost 4e-5 of w to its rounding (round-off
    bound 4e-15), exact-higher-order 2.2e-5 of it."""
    span = (0.7 + width) - 0.7  # the span the floats hold (1.0000889e-12 for 1e-12)
    d = scene_dict("clamped", "free", [{"type": "distributed", "value": -1.0 / span, "start": 0.7, "end": 0.7 + width}])
    spread = run(parse_scene(d), model, points=41)
    d["loads"] = [{"type": "point_force", "position": 0.7 + span / 2, "value": -1.0}]
    point = run(parse_scene(d), model, points=41)
    tip = abs(point.w[-1])
    assert tip > 0
    assert abs(spread.w[-1] - point.w[-1]) <= 1e-6 * tip, (spread.w[-1], point.w[-1])


@pytest.mark.parametrize("width", [1e-8, 1e-6, 1e-4])
@pytest.mark.parametrize("model", ["fem-eb", "fem-timoshenko"])
def test_the_beam_elements_keep_a_narrow_span_s_resultant(model, width):
    """A span end within 1e-12 L of a grid node is taken on it, one ulp of 0.7 m away here: the load kept its value
    over the shorter element and lost ulp / width of its resultant (1.1e-8 of w at a 1e-8 m span, round-off bound
    3.6e-15). It keeps its resultant: the element solution is nodally exact, so fem-eb equals exact-eb to its
    round-off bound (fem-timoshenko exact-timoshenko)."""
    load = {"type": "distributed", "value": -1.0 / width, "start": 0.7, "end": 0.7 + width}
    sc = parse_scene(scene_dict("clamped", "free", [load]))
    fem = run(sc, model, points=41)
    exact = run(sc, "exact-eb" if model == "fem-eb" else "exact-timoshenko", points=41)
    x = np.asarray(fem.x)
    on = np.isin(x, np.asarray(exact.x))
    diff = np.abs(np.asarray(fem.w)[on] - exact.w).max() / np.abs(exact.w).max()
    assert diff <= 3 * fem.info["error_bound"] + 64 * np.finfo(float).eps, (diff, fem.info["error_bound"])


@pytest.mark.parametrize("width", [3e-9, 1e-8, 1e-6])
def test_exact_higher_order_keeps_a_narrow_span_s_resultant(width):
    """exact-higher-order computes in depths: a / h and b / h, each rounded, made a 3e-9 m span's resultant one ulp
    of 7 depths off, 1.5e-8 of w (round-off bound 3.8e-11). It keeps the span's resultant as given: the same as a
    point force in its middle to within its bound and the O((width / L)^2) between the two."""
    span = (0.7 + width) - 0.7
    d = scene_dict("clamped", "free", [{"type": "distributed", "value": -1.0 / span, "start": 0.7, "end": 0.7 + width}])
    spread = run(parse_scene(d), "exact-higher-order", points=41)
    d["loads"] = [{"type": "point_force", "position": 0.7 + span / 2, "value": -1.0}]
    point = run(parse_scene(d), "exact-higher-order", points=41)
    diff = abs(spread.w[-1] - point.w[-1]) / abs(point.w[-1])
    assert diff <= 3 * spread.info["error_bound"] + (width / L) ** 2, (diff, spread.info["error_bound"])
