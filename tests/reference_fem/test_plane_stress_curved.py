"""fem-plane-stress on curved axes: the huge-radius limit is the straight beam, circular cantilevers against
closed-form curved-beam theory (Castigliano with Winkler bending, axial and shear energy; thin-ring
theory), a parabolic axis converges under refinement, unsupported inputs are rejected, VTU output."""

import numpy as np
import pytest
from helpers import MIXED_LOADS, PAIRS, ROOT, scene_dict

from pdverify.core.errors import InputError
from pdverify.core.geometry import axis_length
from pdverify.core.scene import Axis
from pdverify.core.scene_file import load_scene, parse_scene
from pdverify.registry import run

# every load type of the format, incl. axial components, an off-grid force and the global frame
LOADS = [dict(l) for l in MIXED_LOADS] + [
    {"type": "point_force", "position": 0.9, "value": 50.0, "axial": 2000.0},
    {"type": "distributed", "value": 0.0, "axial": -3000.0, "start": 0.4, "end": 1.7},
]
GLOBAL_TIP = (5000.0, 10.0)  # (axial, value) of a global-frame tip force on the straight beam


def _rot(deg):
    c, s = np.cos(np.deg2rad(deg)), np.sin(np.deg2rad(deg))
    return np.array([[c, -s], [s, c]])


@pytest.mark.parametrize("tilt", [0.0, 30.0])
@pytest.mark.parametrize("left,right", PAIRS)
@pytest.mark.slow
def test_huge_radius_arc_equals_straight(left, right, tilt):
    """An arc of radius 1e7 m (L/R = 2e-7) starting with tangent angle `tilt` is the straight beam, turned:
    local w, u and rotation equal the straight ones, global (ux, uy) are the straight (u, w) turned by `tilt`
    (tilt 30° puts every guided/roller constraint in a rotated frame). Measured: <= 3.4e-5 of the largest
    value at tilt 0 (the difference shrinks as 1/R down to R = 1e7: 8e-4 at 1e5, 8e-5 at 1e6; round-off
    floor ~1e-5 at 1e8)."""
    R, L = 1.0e7, 2.0
    gx, gy = _rot(tilt) @ np.array(GLOBAL_TIP)
    straight = parse_scene(
        scene_dict(
            left,
            right,
            LOADS
            + [
                {
                    "type": "point_force",
                    "position": L,
                    "axial": GLOBAL_TIP[0],
                    "value": GLOBAL_TIP[1],
                    "frame": "global",
                }
            ],
        )
    )
    arc = parse_scene(
        scene_dict(
            left,
            right,
            LOADS + [{"type": "point_force", "position": L, "axial": gx, "value": gy, "frame": "global"}],
            axis={
                "type": "arc",
                "radius": R,
                "opening_angle_deg": float(np.rad2deg(L / R)),
                "start_angle_deg": tilt - 90.0,
            },
        )
    )
    a = run(straight, "fem-plane-stress", element="q8", points=41, layers=4)
    b = run(arc, "fem-plane-stress", element="q8", points=41, layers=4)
    assert np.allclose(a.x, b.x, rtol=0, atol=1e-12)
    for key, va, vb in (("w", a.w, b.w), ("u", a.fields["u"], b.fields["u"]), ("rotation", a.rotation, b.rotation)):
        err = np.abs(va - vb).max() / np.abs(va).max()
        assert err < 1e-4, (key, err)
    ga = _rot(tilt) @ np.vstack([a.fields["u"], a.w])
    gb = np.vstack([b.fields["ux"], b.fields["uy"]])
    assert np.abs(ga - gb).max() / np.abs(ga).max() < 1e-4


def castigliano_tip(R, h, b, E, G, k, theta, F, thin=False):
    """Tip displacement (global x, y) of a circular cantilever, centre at the origin, clamped at φ = 0
    (point (R, 0)), free at φ = θ, loaded by the global force F at the free end (unit-load method).

    Section at φ: tangent t = (-sin φ, cos φ), normal n = -(cos φ, sin φ) (inward); resultants from the free
    part: N = F·t, V = F·n, M = (X(θ) - X(φ)) × F (positive: tension on the outer fibre).
    Winkler–Bach (plane sections, hoop stress only): σ(r) = p + q/r on r in [R - h/2, R + h/2]. With
    A = b h, A_m = ∫dA/r = b ln((R + h/2)/(R - h/2)): N = p A + q A_m and M = ∫σ (r - R) dA = q (A - R A_m),
    so q = M / (A - R A_m), p = (N - q A_m) / A. Complementary energy per radian
    ∫σ²/(2E) r dA = [p² R A + 2 p q A + q² A_m] / (2E) (axial, bending and their coupling, exact for the
    Winkler stress); shear: V² R / (2 k G A) (straight-beam parabolic shear, k = 5/6).
    Castigliano / unit load: δ·e = ∫_0^θ {[p p_e R A + (p q_e + p_e q) A + q q_e A_m] / E + V V_e R / (k G A)} dφ,
    with (p_e, q_e, V_e) of a unit force e at the tip; the integrand is a trigonometric polynomial,
    integrated exactly by 40-point Gauss–Legendre. thin=True: thin-ring theory ∫ M M_e R / (E I) dφ
    (for a semicircle with a radial tip force P: δ = π P R³ / (2 E I) along P, 2 P R³ / (E I) across).
    """
    gx, gw = np.polynomial.legendre.leggauss(40)
    phi = theta * (gx + 1) / 2
    wq = theta / 2 * gw
    A, I = b * h, b * h**3 / 12
    Am = b * np.log((R + h / 2) / (R - h / 2))
    X = R * np.stack([np.cos(phi), np.sin(phi)])
    Xt = R * np.array([np.cos(theta), np.sin(theta)])
    t = np.stack([-np.sin(phi), np.cos(phi)])
    n = -np.stack([np.cos(phi), np.sin(phi)])

    def resultants(f):
        f = np.asarray(f, float)
        return f @ t, f @ n, (Xt[0] - X[0]) * f[1] - (Xt[1] - X[1]) * f[0]

    N1, V1, M1 = resultants(F)
    out = []
    for e in np.eye(2):
        Ne, Ve, Me = resultants(e)
        if thin:
            dens = M1 * Me / (E * I) * R
        else:
            q1, qe = M1 / (A - R * Am), Me / (A - R * Am)
            p1, pe = (N1 - q1 * Am) / A, (Ne - qe * Am) / A
            dens = (p1 * pe * R * A + (p1 * qe + pe * q1) * A + q1 * qe * Am) / E + V1 * Ve * R / (k * G * A)
        out.append(float(np.sum(dens * wq)))
    return np.array(out)


def arc_cantilever(R, h, degrees, load):
    L = R * np.deg2rad(degrees)
    return parse_scene(
        scene_dict(
            "clamped",
            "free",
            [dict(load, position=L)],
            beam={"length": L},
            section={"width": 0.05, "height": h},
            axis={"type": "arc", "radius": R, "opening_angle_deg": degrees},
        )
    )


@pytest.mark.parametrize("kind", ["radial", "tangential"])
def test_thick_quarter_circle_against_castigliano(kind):
    """Quarter circle, R = 1 m, R/h = 5, clamped at (R, 0), 1 kN at the free end along the inward normal
    (radial) or the tangent. q8 80 x 8 against castigliano_tip: measured 6.1e-4 (radial) and 6.9e-4
    (tangential) of |δ| (2D clamp and shear distribution; 6e-4 / 9e-4 at 320 x 16). Thin-ring theory is
    4.6e-3 / 2.0e-2 off here, so the axial, coupling and shear terms are what the 3e-3 tolerance checks."""
    R, h, th = 1.0, 0.2, np.pi / 2
    load = {
        "type": "point_force",
        "value": -1000.0 if kind == "radial" else 0.0,
        "axial": 1000.0 if kind == "tangential" else 0.0,
    }
    sc = arc_cantilever(R, h, 90.0, load)
    tip_t, tip_n = np.array([-np.sin(th), np.cos(th)]), -np.array([np.cos(th), np.sin(th)])
    F = load["value"] * tip_n + load["axial"] * tip_t
    E, G = sc.material.E, sc.material.G
    full = castigliano_tip(R, h, 0.05, E, G, 5 / 6, th, F)
    thin = castigliano_tip(R, h, 0.05, E, G, 5 / 6, th, F, thin=True)
    r = run(sc, "fem-plane-stress", element="q8", points=81, layers=8)
    tip = np.array([r.fields["ux"][-1], r.fields["uy"][-1]])
    err = np.linalg.norm(tip - full) / np.linalg.norm(full)
    assert err < 3e-3, (tip, full, err)
    # local outputs agree with the global ones at the tip
    assert r.w[-1] == pytest.approx(tip @ tip_n, rel=1e-12) and r.fields["u"][-1] == pytest.approx(
        tip @ tip_t, rel=1e-12
    )
    if kind == "tangential":
        assert np.linalg.norm(thin - full) / np.linalg.norm(full) > 1e-2  # the thick-beam terms matter here


def test_semicircle_thin_ring():
    """Semicircle, R = 1 m, R/h = 20, clamped at (R, 0), radial tip force P = -100 N along the inward normal
    (n = +x at the tip (-R, 0)): thin-ring theory δx = π P_x R³ / (2 E I), δy = -2 P_x R³ / (E I).
    Measured (q8 160 x 8): 2.8e-4 of |δ| (Winkler + shear formula: 1.4e-4)."""
    R, h = 1.0, 0.05
    sc = arc_cantilever(R, h, 180.0, {"type": "point_force", "value": -100.0})
    Px = -100.0 * 1.0  # tip normal = (1, 0)
    EI = sc.material.E * 0.05 * h**3 / 12
    exact = np.array([np.pi * Px * R**3 / (2 * EI), -2 * Px * R**3 / EI])
    assert castigliano_tip(
        R, h, 0.05, sc.material.E, sc.material.G, 5 / 6, np.pi, [Px, 0.0], thin=True
    ) == pytest.approx(exact, rel=1e-12)
    r = run(sc, "fem-plane-stress", element="q8", points=161, layers=8)
    tip = np.array([r.fields["ux"][-1], r.fields["uy"][-1]])
    assert np.linalg.norm(tip - exact) / np.linalg.norm(exact) < 2e-3


PARABOLA = {"type": "polynomial", "coefficients": [0.0, 0.0, 0.25], "x_range": [0.0, 2.0]}


def test_parabolic_axis_converges(record_property):
    """y = x²/4 on [0, 2] (L = 2.2956 m, slope up to 1), clamped-free, global-frame uniform load, a partial
    sine load, tip force with an axial part and a tip moment (tractions: no point singularity), q8 meshes
    16x2, 32x4, 64x8, 128x16; w at the 17 common stations. Measured max differences 9.0e-6, 2.1e-6, 6.6e-7,
    observed orders 2.07, 1.70: the clamped face's corner singularities cap the rate near
    1.5 as for the straight beam (tests/test_plane_stress.py)."""
    L = axis_length(Axis(**PARABOLA))
    loads = [
        {"type": "distributed", "value": -400.0, "frame": "global"},
        {"type": "distributed", "value": 300.0, "shape": "sine", "start": L / 4, "end": 3 * L / 4},
        {"type": "point_force", "position": L, "value": -200.0, "axial": 500.0},
        {"type": "point_moment", "position": L, "value": 80.0},
    ]
    sc = parse_scene(scene_dict("clamped", "free", loads, beam={"length": L}, axis=PARABOLA))
    stations = np.linspace(0, L, 17)
    ws = []
    for n, k in ((16, 2), (32, 4), (64, 8), (128, 16)):
        r = run(sc, "fem-plane-stress", element="q8", points=n + 1, layers=k)
        idx = [int(np.argmin(np.abs(r.x - s))) for s in stations]
        assert np.allclose(r.x[idx], stations, atol=1e-12 * L)
        ws.append(r.w[idx])
    d = [np.abs(ws[i + 1] - ws[i]).max() for i in range(3)]
    orders = [float(np.log2(d[0] / d[1])), float(np.log2(d[1] / d[2]))]
    record_property("differences", d)
    record_property("orders", orders)
    print("parabola q8: differences", d, "orders", orders)
    assert orders[-1] >= 1.5, (d, orders)
    assert d[-1] < 1e-3 * np.abs(ws[-1]).max()


@pytest.mark.parametrize(
    "over,needle",
    [
        ({"section": {"area": 0.005, "inertia": 4e-6}}, "section: the plane-stress reference needs a rectangle"),
        (  # a profile: the declared shapes' one line, not a second one beside it (sweep 32 B2)
            {"section": {"shape": "profile", "y": [0.0, 0.2, 0.2, 0.24], "b": [0.02, 0.02, 0.15, 0.15]}},
            "section.shape = 'profile': model fem-plane-stress takes a rectangle",
        ),
        ({"section": {"width": 0.05, "height": 2.5}}, "section.height = 2.5"),
        ({"supports": {"left": "pinned", "right": "roller"}}, "rigid rotation about (1, 0)"),
        ({"supports": {"left": "free", "right": "pinned"}}, "rigid rotation about (-1, 0)"),
    ],
)
def test_unsupported_curved_inputs_rejected(over, needle):
    """A semicircle (R = 1, from (1, 0) to (-1, 0)) with a section given by area/inertia, a height reaching
    past the centre of curvature, or a support pair leaving a rigid-body motion (pinned-roller: the right
    roller's normal is the diameter, through the left pin, so the rotation about the pin is free) is
    rejected before solving, with the field named (mechanisms already by the scene validator)."""
    d = scene_dict(
        "clamped",
        "free",
        [{"type": "point_force", "position": np.pi, "value": -100.0}],
        beam={"length": np.pi},
        axis={"type": "arc", "radius": 1.0, "opening_angle_deg": 180.0},
    )
    d.update(over)
    with pytest.raises(InputError) as exc:
        run(parse_scene(d), "fem-plane-stress", points=21, layers=2)
    assert needle in str(exc.value) and len(exc.value.lines) == 1, exc.value.lines


def test_quarter_circle_pinned_pinned_solves():
    """Pinned-pinned on a quarter circle is stable (the roller's normal is not across the pin rotation)."""
    d = scene_dict(
        "pinned",
        "pinned",
        [{"type": "distributed", "value": -100.0, "frame": "global"}],
        beam={"length": np.pi / 2},
        axis={"type": "arc", "radius": 1.0, "opening_angle_deg": 90.0},
    )
    r = run(parse_scene(d), "fem-plane-stress", element="q8", points=41, layers=4, pin="node")
    assert np.all(np.isfinite(r.w)) and abs(r.w[0]) < 1e-15 and abs(r.w[-1]) < 1e-15


@pytest.mark.parametrize("name", ["quarter_circle_tip_force", "semicircle_radial_force", "parabola_uniform"])
def test_curved_scene_files_and_vtu(name, tmp_path):
    import meshio

    sc = load_scene(ROOT / "studies" / "curved" / f"{name}.toml")
    r = run(sc, "fem-plane-stress", element="q8", points=41, layers=4)
    assert r.info["axis"] == sc.axis.type and np.all(np.isfinite(r.w))
    r.writers[".vtu"](str(tmp_path / "r.vtu"))
    m = meshio.read(tmp_path / "r.vtu")
    n = m.points.shape[0]
    assert m.point_data["displacement"].shape == (n, 3) and np.all(m.point_data["von_mises"] >= 0)
    assert list(m.cells_dict) == ["quad8"]  # the mid-side nodes kept (on the mapped curves)
    # the VTU carries the mapped (curved) geometry: mid-line points lie on the axis
    from pdverify.core.geometry import geometry

    X = geometry(sc).position(np.array([0.0, sc.length]))
    for p in X:
        assert np.min(np.hypot(m.points[:, 0] - p[0], m.points[:, 1] - p[1])) < 1e-12 * sc.length


def beam_load_resultant(scene):
    """(Fx, Fy, Mz about X(0)) of the scene's loads on the axis, by 400-point Gauss per distributed load."""
    from pdverify.core.geometry import geometry
    from pdverify.core.scene import Distributed, PointForce

    geo = geometry(scene)
    X0 = geo.position(np.array([0.0]))[0]
    gx, gw = np.polynomial.legendre.leggauss(400)
    total = np.zeros(3)

    def add(s, f):  # forces f (n, 2) at stations s (n,)
        r = geo.position(s) - X0
        total[:2] += f.sum(axis=0)
        total[2] += np.sum(r[:, 0] * f[:, 1] - r[:, 1] * f[:, 0])

    for load in scene.loads:
        if isinstance(load, Distributed):
            a, b = scene.span(load)
            s = (a + b) / 2 + (b - a) / 2 * gx
            prof = np.ones_like(s) if load.shape == "uniform" else np.sin(np.pi * s / scene.length)
            wts = (b - a) / 2 * gw * prof
        elif isinstance(load, PointForce):
            s, wts = np.array([load.position]), np.ones(1)
        else:
            total[2] += load.value
            continue
        t, n = geo.frame(s)
        if load.frame == "global":
            f = np.tile([load.axial, load.value], (len(s), 1))
        else:
            f = load.axial * t + load.value * n
        add(s, f * wts[:, None])
    return total


@pytest.mark.parametrize("axis", ["arc", "parabola"])
@pytest.mark.parametrize("element", ["q4", "q8", "q9"])
@pytest.mark.slow
def test_assembled_loads_have_the_beam_resultant(axis, element):
    """Every load type (local and global frame, partial uniform and sine spans, off-grid forces, interior and
    end moments, axial parts) on a curved axis: the assembled nodal forces have the force and moment of the
    beam loads, computed independently on the axis (top-face tractions are per unit axis length, shear
    tractions lie along n, so the offsets carry no extra moment).
    Point forces and moments: round-off (measured <= 5e-16). Distributed loads: the forces to round-off; the
    moment of work-equivalent nodal forces differs from the continuous one by the lumping error, measured
    q4 (straight chords) 2.5e-4, 6.6e-5 (31, 61 points; order 2), q8/q9 5.7e-9, 3.9e-10 (order ~4)."""
    if axis == "arc":
        L, ax = (
            2.0,
            {"type": "arc", "radius": 1.5, "opening_angle_deg": float(np.rad2deg(2.0 / 1.5)), "start_angle_deg": -60.0},
        )
    else:
        L, ax = axis_length(Axis(**PARABOLA)), PARABOLA
    loads = [dict(l) for l in LOADS if l.get("position", 0.0) <= L and l.get("end", 0.0) <= L] + [
        {"type": "distributed", "value": -250.0, "axial": 40.0, "frame": "global", "start": 0.3, "end": 1.2},
        {"type": "distributed", "value": 120.0, "axial": -70.0, "shape": "sine", "frame": "global"},
        {"type": "point_force", "position": 1.37, "value": 90.0, "axial": -30.0, "frame": "global"},
        {"type": "point_force", "position": L, "value": -60.0, "axial": 25.0},
        {"type": "point_force", "position": 0.0, "value": 45.0, "axial": 15.0, "frame": "global"},
        {"type": "point_moment", "position": L, "value": 33.0},
    ]

    def errors(sel, points):
        sc = parse_scene(scene_dict("clamped", "free", [l for l in loads if sel(l)], beam={"length": L}, axis=ax))
        ref = beam_load_resultant(sc)
        got = np.array(run(sc, "fem-plane-stress", element=element, points=points, layers=4).info["load_resultant"])
        return np.abs(got - ref) / np.abs(ref).max()

    point = errors(lambda l: l["type"] != "distributed", 31)
    assert point.max() < 1e-12, point
    d31, d61 = errors(lambda l: l["type"] == "distributed", 31), errors(lambda l: l["type"] == "distributed", 61)
    assert d31[:2].max() < 1e-12 and d61[:2].max() < 1e-12  # forces
    order = np.log2(d31[2] / d61[2])
    if element == "q4":
        assert d31[2] < 5e-4 and order > 1.8, (d31, d61)
    else:
        assert d31[2] < 1e-8 and order > 3.5, (d31, d61)


@pytest.mark.parametrize("sl,tol", [(5, 1e-3), (20, 1e-4)])
@pytest.mark.slow
def test_face_pin_matches_timoshenko_goodier(sl, tol):
    """Option pin = face (straight beam, pinned-pinned, uniform load q on the top face) against the 2D
    elasticity solution of Timoshenko & Goodier (Theory of Elasticity, §22, plane stress, span 2l = L,
    depth 2c = h): w(L/2) = 5 q L⁴ / (384 E I) [1 + 12/5 (h/L)² (4/5 + ν/2)].
    Measured (q8 160 x 16): -4.2e-4 (L/h = 5; their end condition is the point value, ours the weighted
    mean) and -1.8e-6 (L/h = 20). The default pin = node diverges like log(1/element size): -1.26e-7 m per
    halving here, 1 % of w at L/h = 5, so at 320 x 32 it is 5 % off (asserted below). pin = face is the default."""
    from helpers import scene_dict as sd

    # their beam is free to extend axially: pinned-roller (two pins would add the Poisson-induced axial force)
    sc = parse_scene(sd("pinned", "roller", [{"type": "distributed", "value": -1000.0}])).with_slenderness(sl)
    L, h, nu = sc.length, sc.section.height, sc.material.poissons_ratio
    exact = 5 * -1000.0 * L**4 / (384 * sc.EI) * (1 + 12 / 5 * (h / L) ** 2 * (4 / 5 + nu / 2))
    r = run(sc, "fem-plane-stress", element="q8", points=161, layers=16, pin="face")
    w = r.w[np.argmin(np.abs(r.x - L / 2))]
    assert abs(w / exact - 1) < tol, w / exact - 1
    if sl == 5:
        rn = [
            run(sc, "fem-plane-stress", element="q8", points=n + 1, layers=k, pin="node") for n, k in ((40, 4), (80, 8))
        ]
        wn = [x.w[np.argmin(np.abs(x.x - L / 2))] for x in rn]
        assert (wn[1] - wn[0]) / exact > 5e-3  # the node pin keeps moving by ~1 % per halving


@pytest.mark.slow
def test_face_pin_converges_on_a_curved_arch(record_property):
    """Quarter-circle two-pinned arch (R = 1, R/h = 10), global downward uniform load, pin = face, q8
    20x2 .. 160x16: the mid-line deflection converges at a high rate (no point reaction); measured (both
    ends held in t and n) differences 1.0e-8, 6.6e-10, 4.1e-11 m, orders 3.98, 3.99 — while pin = node
    changes by ~2e-7 m per halving (orders -0.15, -0.02). Before pinned meant one thing at both ends (the
    right pin was a roller): 7.6e-8, 4.8e-9, 3.1e-10 m; node 7.2e-8 m per halving."""
    d = scene_dict(
        "pinned",
        "pinned",
        [{"type": "distributed", "value": -1000.0, "frame": "global"}],
        beam={"length": np.pi / 2},
        section={"width": 0.05, "height": 0.1},
        axis={"type": "arc", "radius": 1.0, "opening_angle_deg": 90.0},
    )
    sc = parse_scene(d)
    stations = np.linspace(0, sc.length, 21)
    out = {}
    for pin in ("face", "node"):
        ws = []
        for n, k in ((20, 2), (40, 4), (80, 8), (160, 16)):
            r = run(sc, "fem-plane-stress", element="q8", points=n + 1, layers=k, pin=pin)
            ws.append(r.w[[int(np.argmin(np.abs(r.x - s))) for s in stations]])
        diffs = [np.abs(ws[i + 1] - ws[i]).max() for i in range(3)]
        out[pin] = (diffs, [float(np.log2(diffs[i] / diffs[i + 1])) for i in range(2)])
    record_property("face_pin", out["face"])
    record_property("node_pin", out["node"])
    assert out["face"][1][-1] > 3.0, out
    assert out["node"][1][-1] < 0.5, out  # the log-divergent point reaction, for contrast
