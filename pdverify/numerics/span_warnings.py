"""The moment and shear of a short span between two supports that hold the deflection.

Between two such supports a distance a apart the moment and shear of a PD beam carry an error of about
c (h / a)² times their largest value in that span (h = max(spacing, horizon / 3)): second order, but with the span,
not the beam, as the length, so a support placed close to an end or to another support leaves them off by far more
than the rest of the beam at the same grid. Measured (docs/trust.md, Random scenes: "The moment and shear of a short
span"; benchmarks/short_spans.py): pd-eb and pd-timoshenko on spans of 0.02-0.08 L beside an end or between two
supports inside, pinned, clamped and springs, under point forces and a uniform load, 101-801 points."""

import numpy as np

from ..core.scene import HELD, Scene
from ..core.text import rounded_up, spacings
from .load_warnings import NEAR_TOLERANCE
from .loads import within

QUANTITIES = ("V", "M")


# k a³ / EI from which a spring holds the deflection like a support, kr a / EI from which it holds the rotation (a the
# span beside it): a spring of k a³ / EI = 30 already leaves 85-95 % of a rigid one's error in the span, one of
# kr a / EI = 1.5 the clamp's constant (benchmarks/short_spans.py)
RIGID = {"k": 10.0, "kr": 1.0}


def spring_share(kappa: float) -> float:
    """The share of a rigid support's span error that a spring of k a³ / EI = ``kappa`` below ``RIGID["k"]`` leaves
    beside it, (kappa / RIGID["k"])^(1/3): measured at most 0.64, 0.31, 0.19 of the rigid estimate at kappa = 3, 1, 0.3
    (pd-eb and pd-timoshenko, a spring 0.02-0.08 L from a clamp or a pin inside or a clamped end, a force or a uniform
    load, 201-801 points, horizons 3 and 4: docs/trust.md; the cube root 0.67, 0.46, 0.31)."""
    return min(1.0, max(kappa, 0.0) / RIGID["k"]) ** (1.0 / 3.0)


def span_bounds(scene: Scene, soft: bool = False) -> list[tuple]:
    """(position, name, holds the rotation, inside the beam) of the supports that hold the deflection, left to right:
    the named ends that do (:data:`~pdverify.core.scene.HELD`), the pinned, roller and clamped supports inside, and the
    springs (at an end or inside) stiff beside the span next to them, k a³ / EI of at least :data:`RIGID` (a the
    distance to the nearest other support; a rotational stiffness kr holds the rotation where kr a / EI is).
    ``soft``: the softer springs too, each with a fifth entry, its :func:`spring_share` (1 for the others)."""
    L = scene.length
    rigid, springs = [], []
    for side, at in (("left", 0.0), ("right", L)):
        kind, sup = scene.supports.kind(side), getattr(scene.supports, side)
        if kind != "spring" and HELD[kind][1]:
            rigid.append((at, f"the {side} end ({kind})", HELD[kind][2], False))
        elif kind == "spring" and sup.stiffness:
            springs.append((at, f"the {side} end (spring)", sup.stiffness, sup.rotational_stiffness, False))
    for i, s in enumerate(scene.supports.inner):
        if s.type != "spring":
            rigid.append((s.position, f"supports.inner[{i}] ({s.type})", s.type == "clamped", True))
        elif s.stiffness:
            springs.append((s.position, f"supports.inner[{i}] (spring)", s.stiffness, s.rotational_stiffness, True))
    everywhere = [b[0] for b in rigid] + [b[0] for b in springs]
    out = [(*b, 1.0) for b in rigid]
    for at, name, k, kr, inner in springs:
        a = min((abs(p - at) for p in everywhere if p != at), default=L)
        EI = float(scene.stiffness_at(np.array([at]))["EI"][0])
        if k * a**3 / EI >= RIGID["k"] or soft:
            out.append((at, name, bool(kr) and kr * a / EI >= RIGID["kr"], inner, spring_share(k * a**3 / EI)))
    return sorted(out if soft else [b[:4] for b in out], key=lambda b: b[0])


def spans(scene: Scene) -> list[tuple[tuple, tuple, float]]:
    """(left bound, right bound, share) of each span :func:`short_span_warnings` judges: the neighbouring pairs of
    :func:`span_bounds` (share 1), and each softer spring's span to its neighbour on either side among them all, at its
    :func:`spring_share` (the smaller of two springs'; the span between two stiff supports is kept whole beside it)."""
    rigid = span_bounds(scene)
    out = [(p, q, 1.0) for p, q in zip(rigid, rigid[1:])]
    every = span_bounds(scene, soft=True)
    for p, q in zip(every, every[1:]):
        if min(p[4], q[4]) < 1.0:
            out.append((p[:4], q[:4], min(p[4], q[4])))
    return sorted(out, key=lambda s: (s[0][0], s[1][0]))


def short_span_warnings(
    scene: Scene,
    x: np.ndarray,
    fields: dict,
    delta: float,
    constants: dict,
    shortest: tuple = (0.0, 0.0),
    fixed_horizon: bool = False,
    inside_only: bool = False,
) -> list[str]:
    """One line per span between two neighbouring supports that hold the deflection (:func:`span_bounds`), one of them
    inside the beam, whose estimate c (h / a)² max_span |q| / max |q| passes NEAR_TOLERANCE for the shear or the moment
    q (max_span: over the span and a horizon beyond each of its ends; ``fields`` "V" and "M", the model's own on the
    points ``x``; h = max(spacing, ``delta`` / 3), a the span's length;
    ``constants`` {"held": {"V": c, "M": c}, "pinned": {...}}: "held" where a support of the span holds the
    rotation). Spans under ``shortest`` = (beside an end, between two supports inside) spacings are left to the
    model's own layer and straddle lines (where the estimate does not hold). ``fixed_horizon``: the horizon is a given
    length, so more points do not shrink h below delta / 3 and the fix named is a shorter horizon. ``inside_only``:
    only a support inside the beam that holds the rotation makes the span "held" (pd-eb: a clamped end beside a pin
    inside keeps the pin's constant)."""
    dx = float(x[1] - x[0])
    h = max(dx, delta / 3.0)
    size = {name: np.abs(np.asarray(fields[name], dtype=float)) for name in QUANTITIES}
    top = {name: float(f.max()) if f.size else 0.0 for name, f in size.items()}
    out = []
    for (p, left, held_left, inner_left), (q, right, held_right, inner_right), share in spans(scene):
        a = q - p
        if not (inner_left or inner_right) or within(a, shortest[inner_left and inner_right], dx):
            continue
        # the families reach a horizon across each support: its reaction's jump counts whether or not a point
        # carries it (a span between points holds little of its own shear where it is unloaded)
        reach = max(delta, dx) * (1 + 1e-9)
        inside = (x >= p - reach) & (x <= q + reach)
        held = (held_left and (inner_left or not inside_only)) or (held_right and (inner_right or not inside_only))
        c = constants["held" if held else "pinned"]
        shares = {}
        for name in QUANTITIES:
            if top[name] > 0.0 and inside.any():
                shares[name] = share * c[name] * (h / a) ** 2 * float(size[name][inside].max()) / top[name]
        est = {k: v for k, v in shares.items() if v > NEAR_TOLERANCE}
        if not est:
            continue
        target = h * np.sqrt(NEAR_TOLERANCE / max(est.values())) / 1.1  # the h that brings it to 1e-3
        if fixed_horizon and delta / 3.0 > target:
            fix = f"a spacing of at most {target:.3g} and horizon_length at most {3 * target:.3g}"
        else:
            fix = f"at least {int(np.ceil(scene.length / (dx * target / h))) + 1} points"  # h in proportion to dx
        said = ", ".join(f"{k} {rounded_up(v)} of max |{k}|" for k, v in est.items())
        form = ", ".join(f"{k} {c[k]:g}" for k in est)
        soft = "" if share == 1.0 else f", times {share:.2g} for a spring softer than {RIGID['k']:g} EI / a³"
        out.append(
            f"the span of {a:g} ({spacings(a / dx)}) between {left} at {p:g} and {right} at {q:g}: its moment "
            f"and shear are off by about c (h / a)² times their largest in and beside the span{soft} (h = "
            "max(spacing, horizon / 3), "
            f"a the span; c: {form}), here {said}; second order: use {fix} for 1e-3"
        )
    return out
