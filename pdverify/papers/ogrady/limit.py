"""Where the bond-pair beam has a nonlocal continuum at a fixed horizon (docs/nonlocal.md, "A limit at fixed δ?").

With omega = 1 and alpha = 3 EI / delta^3 (O'Grady & Foster 2014, Eq. 5) the continuous symbol is
(3 EI / delta^3) ∫_0^delta 16 sin^4(k xi / 2) / xi^2 d xi (docs/design/nonlocal.md), which grows like
6 pi EI |k| / delta^3 at large k (∫_0^inf 16 sin^4(u / 2) / u^2 du = 2 pi); a weight that vanishes at xi = 0
(the section weight omega = |xi| b) grows more slowly still. The response at the point of a point force P,
(1 / pi) ∫^K dk / symbol, then grows without bound as the grid's cut-off K ~ pi / dx rises: like
P delta^3 ln(m) / (6 pi^2 EI) for omega = 1, i.e. by P delta^3 ln 2 / (6 pi^2 EI) per doubling of m at fixed delta.
So at a fixed horizon the discrete solutions have no limit wherever a single point carries a force: a point force or
moment, a prescribed deflection, a support inside the span, a spring, and an end point held by its own reaction
(a clamped end with mirror ghosts, whose even image leaves w = 0 to the held point; any held end with no ghosts).
Pinned ends with mirror ghosts are held by their odd image and keep a limit.

Taylor ghost ends (docs/design/formulas.md §1) at a free or guided end fit the end's polynomial to the first points
and carry it over the whole horizon: at fixed delta the fit has no limit in m (measured in docs/nonlocal.md, not
derived), so those scenes have none either.
"""

from __future__ import annotations

from ...core.scene import Scene

POINT_LOADS = ("point_force", "point_moment", "displacement")


def end_kinds(scene: Scene) -> set[str]:
    """The supports of the scene's two ends (names of :data:`pdverify.core.scene.SUPPORTS` or "spring")."""
    return {scene.supports.kind(side) for side in ("left", "right")}


def no_limit_reason(scene: Scene, ends: str) -> str:
    """Why the bond-pair beam with (resolved) ``ends`` has no limit at fixed delta on ``scene``, "" when it has one."""
    kinds = end_kinds(scene)
    loads = sorted({ld.type.replace("_", " ") for ld in scene.loads if ld.type in POINT_LOADS})
    held = []
    if loads:
        held.append(f"a {' and a '.join(loads)}")
    if scene.supports.inner:
        held.append("a support inside the span")
    if "spring" in kinds:
        held.append("a spring")
    if ends == "mirror" and "clamped" in kinds:
        held.append("a clamped end (its mirror image leaves the deflection to the held end point)")
    if ends == "none" and kinds & {"clamped", "pinned", "roller"}:
        held.append("a held end without ghosts")
    if held:
        return (
            f"{', '.join(held)}: a single point carries a force, and the bond-pair symbol grows like 6 pi EI |k| / "
            "delta^3, so the deflection there grows like ln m at fixed delta (docs/nonlocal.md): no limit"
        )
    if ends == "taylor" and kinds & {"free", "guided"}:
        return "Taylor ghost ends at a free or guided end have no limit at fixed delta (docs/nonlocal.md)"
    return ""
