"""The warning of two rigid supports closer than the beam's depth: how the load splits between them is a property of
the beam theory, not of the beam. Two supports d apart hold the beam like a clamp of width d: Euler–Bernoulli theory
turns the couple between them into reactions of order M / d, Timoshenko theory's shear compliance over d spreads them
evenly, and a plane-stress strip (or the real support) gives something else again. Their sum, and the deflection
away from them, differ between the theories no more than elsewhere (docs/supports.md, "Supports close together")."""

from __future__ import annotations

from ..core.errors import SolveError
from ..core.scene import Scene
from ..exact.straight import solve_straight

SPLIT = 0.05  # the two theories' reactions apart by more than this fraction of the pair's sum: the split is warned


def rigid_stations(scene: Scene) -> list[tuple[float, str]]:
    """(position, reaction key) of every support that holds the deflection, ends and inside the span: rigidly, or a
    spring inside whose split against its neighbour the two theories' reactions then judge (a stiff one splits as a
    rigid support does, a soft one as the theories agree)."""
    out = [(0.0, "force_left")] * scene.supports.holds_deflection_at("left")
    out += [(s.position, f"force_inner_{i}") for i, s in enumerate(scene.supports.inner) if s.holds_deflection]
    out += [(scene.length, "force_right")] * scene.supports.holds_deflection_at("right")
    return sorted(out)


def close_supports_warning(scene: Scene) -> str:
    """The one-line warning of two rigid supports closer than the section's depth whose reactions exact
    Euler–Bernoulli and exact Timoshenko split differently (by more than :data:`SPLIT` of their sum), with both
    splits; "" otherwise (a curved axis, a section without a depth, no such pair)."""
    if not scene.is_straight or not scene.supports.inner:
        return ""
    h = scene.section.depth
    at = rigid_stations(scene)
    pairs = [(a, b) for a, b in zip(at, at[1:]) if b[0] - a[0] < h]
    if not pairs:
        return ""
    try:
        eb, ti = (solve_straight(scene, shear).reactions() for shear in (False, True))
    except SolveError:  # the closed forms refuse supports that nearly coincide: the split is then said without numbers
        eb = ti = None
    for (xa, ka), (xb, kb) in pairs:
        split = ""
        if eb is not None:
            total = abs(eb[ka] + eb[kb])
            if max(abs(eb[ka] - ti[ka]), abs(eb[kb] - ti[kb])) <= SPLIT * max(total, 1e-300):
                continue
            split = (
                f" (exact-eb: {eb[ka]:.4g} and {eb[kb]:.4g}, exact-timoshenko: {ti[ka]:.4g} and {ti[kb]:.4g}; "
                f"their sums {eb[ka] + eb[kb]:.4g} and {ti[ka] + ti[kb]:.4g})"
            )
        return (
            f"supports at x = {xa:.12g} and {xb:.12g} are {xb - xa:.3g} apart, {(xb - xa) / h:.3g} depths: how the "
            f"load splits between their reactions {ka} and {kb} is the beam theory's, not the beam's{split}; their sum "
            "and the deflection away from them depend on it no more than on the theory elsewhere (docs/supports.md)"
        )
    return ""
