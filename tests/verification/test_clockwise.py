"""Clockwise arcs and negative curvature: every curved model on mirror-image axes.

A clockwise arc (``direction = "clockwise"``) from start angle 180° - a0 is the reflection about the vertical
line x = 0 of the counter-clockwise arc from a0, with the same arc length s at reflected points
(pdverify/geometry.py). The reflection keeps the tangent's reflected image as the tangent but turns the normal
n = e_z × t into minus the reflected normal, so the mirrored scene has, at the same s: local loads with the normal
value negated and the axial part kept, global loads with the x component (axial) negated and y kept, moments
negated; and every model must return ux -> -ux, uy -> uy, rotation -> -rotation (N -> N, Q -> -Q, M -> -M).
A polynomial y = -c(x) is the reflection of y = c(x) about the x axis: the same load rules with global y
negated instead of x, and ux -> ux, uy -> -uy, rotation -> -rotation.
"""

import numpy as np
import pytest
from helpers import scene_dict

from pdverify.core.errors import InputError
from pdverify.core.geometry import axis_length, geometry
from pdverify.core.scene import Axis
from pdverify.core.scene_file import parse_scene
from pdverify.registry import run

ARC = {"type": "arc", "radius": 1.0, "opening_angle_deg": 120.0, "start_angle_deg": 30.0}
POLY = {"type": "polynomial", "coefficients": [0.0, 0.4, -0.3, 0.1], "x_range": [0.0, 1.6]}


def loads(L: float) -> list[dict]:
    return [
        {"type": "distributed", "value": -1000.0, "frame": "global"},
        {"type": "distributed", "value": 200.0, "axial": 150.0, "start": 0.2 * L, "end": 0.6 * L},
        {"type": "distributed", "value": 300.0, "shape": "sine", "axial": 80.0, "frame": "global"},
        {"type": "point_force", "position": 0.4 * L, "value": 300.0, "axial": -200.0},
        {"type": "point_moment", "position": 0.7 * L, "value": 50.0},
        {"type": "point_force", "position": L, "value": -40.0, "axial": 30.0, "frame": "global"},
    ]


def curved(axis: dict, left: str, right: str, h: float = 0.02) -> dict:
    L = axis_length(Axis(**axis))
    return scene_dict(left, right, loads(L), beam={"length": L}, section={"width": 0.05, "height": h}, axis=axis)


def reflected(d: dict, about: str) -> dict:
    """The scene reflected about the vertical line x = 0 (``about = "y"``: a counter-clockwise arc becomes a
    clockwise one) or about the x axis (``"x"``: polynomial coefficients negated), s kept (module docstring)."""
    out = dict(d, loads=[])
    flipped = "axial" if about == "y" else "value"  # the global component that changes sign
    for load in d["loads"]:
        m = dict(load)
        if m["type"] == "point_moment":
            m["value"] = -m["value"]
        elif m.get("frame") == "global":
            m[flipped] = -m.get(flipped, 0.0)
        else:
            m["value"] = -m["value"]
        out["loads"].append(m)
    a = d["axis"]
    if a["type"] == "arc":
        start = 180.0 - a["start_angle_deg"] if about == "y" else -a["start_angle_deg"]
        turn = "clockwise" if a.get("direction", "counterclockwise") == "counterclockwise" else "counterclockwise"
        out["axis"] = dict(a, start_angle_deg=start, direction=turn)
    else:
        assert about == "x", "a polynomial's reflection about a vertical line reverses s (tests/test_mirror.py)"
        out["axis"] = dict(a, coefficients=[-c for c in a["coefficients"]])
    return out


def mirror_errors(a, b, about: str) -> dict:
    """Relative differences of the reflected fields: displacements against max |u|, rotation against its max."""
    sx, sy = (-1.0, 1.0) if about == "y" else (1.0, -1.0)
    scale = max(np.abs(a.fields["ux"]).max(), np.abs(a.fields["uy"]).max())
    out = {
        "ux": np.abs(a.fields["ux"] - sx * b.fields["ux"]).max() / scale,
        "uy": np.abs(a.fields["uy"] - sy * b.fields["uy"]).max() / scale,
        "rotation": np.abs(a.rotation + b.rotation).max() / np.abs(a.rotation).max(),
    }
    for key, sign in (("N", 1.0), ("Q", -1.0), ("M", -1.0)):
        if key in a.fields:
            out[key] = np.abs(a.fields[key] - sign * b.fields[key]).max() / np.abs(a.fields[key]).max()
    return out


def test_clockwise_arc_geometry_is_the_mirror_image():
    ccw = parse_scene(curved(ARC, "clamped", "free"))
    cw = parse_scene(reflected(curved(ARC, "clamped", "free"), "y"))
    g, h = geometry(ccw), geometry(cw)
    s = np.linspace(0.0, ccw.length, 7)
    assert np.allclose(h.position(s), g.position(s) * [-1.0, 1.0], rtol=0, atol=1e-15)
    (t1, n1), (t2, n2) = g.frame(s), h.frame(s)
    assert np.allclose(t2, t1 * [-1.0, 1.0], rtol=0, atol=1e-15)  # the tangent is reflected
    assert np.allclose(n2, -n1 * [-1.0, 1.0], rtol=0, atol=1e-15)  # the normal is minus the reflected one
    assert np.allclose(h.curvature(s), -1.0) and np.allclose(g.curvature(s), 1.0)
    dth = np.gradient(np.unwrap(h.angle(s)), s)  # curvature = dθ/ds, signed
    assert np.allclose(dth, -1.0)


def test_direction_is_for_arcs_only_and_spelt_out():
    d = curved(POLY, "clamped", "free")
    for axis in (dict(POLY, direction="clockwise"), dict(ARC, direction="cw")):
        with pytest.raises(InputError, match="direction") as exc:
            parse_scene(dict(d, axis=axis))
        assert "\n" not in str(exc.value)
    for d in (curved(POLY, "clamped", "free"), reflected(curved(ARC, "clamped", "free"), "y")):  # to_dict round trip
        sc = parse_scene(d)
        assert parse_scene(sc.to_dict()) == sc


PAIRS = [("clamped", "free"), ("pinned", "roller"), ("clamped", "guided"), ("pinned", "pinned"), ("roller", "clamped")]
# per model: options and the tolerance on every reflected field. Measured worst over the pairs (L/h = 105):
# exact-curved 9e-13 (pinned-pinned: its statically indeterminate solve), pd-curved mixed 9e-16, primal 2.5e-13
# (its N, from second differences of the displacements: 3.9e-10, not compared), fem-plane-stress 1.6e-7: the
# 2D solve's round-off (its own bound, info.error_bound, is 3.1e-5 here; at h = 0.1 the difference is 6e-11).
# With the loads of a clockwise arc on its +n (outer) face instead of the mirrored inner face the plane-stress
# difference was 1e-6 .. 1.8e-4 (the load face is a 2D effect).
MODELS = {
    "exact-curved": ({}, 5e-12),
    "pd-curved mixed": ({"points": 81}, 1e-14),
    "pd-curved primal": ({"points": 81, "form": "primal"}, 2e-12),
    "fem-plane-stress": ({"points": 41, "layers": 4, "element": "q8"}, 1e-6),
}


@pytest.mark.parametrize("label", list(MODELS))
@pytest.mark.parametrize("left, right", PAIRS)
def test_clockwise_arc_gives_the_mirror_image_of_the_counterclockwise_arc(label, left, right):
    opts, tol = MODELS[label]
    name = label.split()[0]
    d = curved(ARC, left, right)
    a, b = run(parse_scene(d), name, **opts), run(parse_scene(reflected(d, "y")), name, **opts)
    assert np.array_equal(a.x, b.x)
    errs = mirror_errors(a, b, "y")
    if label == "pd-curved primal":
        errs.pop("N"), errs.pop("Q")
    assert max(errs.values()) < tol, errs


def test_exact_cantilever_on_a_clockwise_arc():
    """exact-curved-cantilever (statics, no solve) on both ends free in turn."""
    for left, right in (("clamped", "free"), ("free", "clamped")):
        d = curved(ARC, left, right)
        a = run(parse_scene(d), "exact-curved-cantilever", points=101)
        b = run(parse_scene(reflected(d, "y")), "exact-curved-cantilever", points=101)
        errs = mirror_errors(a, b, "y")
        assert max(errs.values()) < 1e-14, errs  # measured


@pytest.mark.parametrize("form, degree, order", [("mixed", 2, 2.0), ("mixed", 4, 4.0), ("primal", 4, 4.0)])
def test_pd_curved_converges_to_exact_curved_on_a_clockwise_arc(form, degree, order):
    """Clamped-pinned clockwise arc (R = 1, 120°, L/h = 10), the six loads: relative error in max |u| at 41, 81,
    161, 321 particles converges at the form's order (mixed P = 2: 2; P = 4: 4), the same errors as on the
    counter-clockwise arc.

    The two arcs' errors may differ only by round-off: each pd-curved solve by its own bound
    (``info["error_bound"]``, relative to max |u|) and exact-curved by the mirror difference asserted above
    (``MODELS["exact-curved"]``), so |cw - ccw| <= the sum of those for the pair of arcs."""
    errs, bounds = {}, {}
    for about in ("y", None):
        d = curved(ARC, "clamped", "pinned", h=0.2)
        sc = parse_scene(reflected(d, about) if about else d)
        for n in (41, 81, 161, 321):
            r = run(sc, "pd-curved", points=n, degree=degree, form=form)
            e = run(sc, "exact-curved", points=n)
            assert np.array_equal(r.x, e.x)
            du = np.hypot(r.fields["ux"] - e.fields["ux"], r.fields["uy"] - e.fields["uy"])
            errs.setdefault(about, []).append(du.max() / np.hypot(e.fields["ux"], e.fields["uy"]).max())
            bounds.setdefault(about, []).append(r.info["error_bound"])
    cw, ccw = np.array(errs["y"]), np.array(errs[None])
    roundoff = np.array(bounds["y"]) + np.array(bounds[None]) + 2 * MODELS["exact-curved"][1]
    assert np.all(np.abs(cw - ccw) <= roundoff), (cw - ccw, roundoff)  # the mirror image's error
    orders = np.log2(cw[:-1] / cw[1:])
    # round-off moves an order by at most (r_n / e_n + r_2n / e_2n) / ln 2: below 0.1, under half the order's band
    shift = (roundoff[:-1] / cw[:-1] + roundoff[1:] / cw[1:]) / np.log(2)
    assert np.all(shift < 0.1), (cw, roundoff)
    assert cw[-1] < 2e-4 and abs(orders[-1] - order) < 0.25, (cw, orders)


@pytest.mark.parametrize("label", ["exact-curved", "pd-curved mixed", "pd-curved primal"])
def test_negative_curvature_polynomial_is_the_reflection_about_the_x_axis(label):
    """y = -c(x) against y = c(x) (a cubic whose curvature changes sign), clamped-pinned: the same tolerances."""
    opts, tol = MODELS[label]
    name = label.split()[0]
    d = curved(POLY, "clamped", "pinned")
    a, b = run(parse_scene(d), name, **opts), run(parse_scene(reflected(d, "x")), name, **opts)
    errs = mirror_errors(a, b, "x")
    if label == "pd-curved primal":
        errs.pop("N"), errs.pop("Q")
    assert max(errs.values()) < tol, errs
