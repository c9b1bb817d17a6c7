"""Where beam theory stops describing the plane-stress solid it stands for on a short beam: the ratio of its length L
to the section's depth h.

A beam theory (Euler–Bernoulli, Timoshenko) holds the section plane and takes no stress through the depth; the solid
does not, within about a depth of a support that holds it, of a concentrated load and of the ends (Saint-Venant's
principle: Timoshenko & Goodier, *Theory of Elasticity*, 3rd ed., ch. 3, the cantilever and the beam under uniform
load by stress functions). Its deflection then differs from the continuum's by c (h/L) of max |w| where such a layer
acts (a clamp, a point load), c (h/L)² where none does (a simply supported beam under a distributed load: the
theories' correction terms). Measured (fem-plane-stress at 161 stations against exact-timoshenko, a 1 m beam):

    | scene                          | L/h = 3 | 5      | 10     | 20     |
    | cantilever, tip force          | 0.81 % | 0.46 % | 0.22 % | 0.11 % |
    | pinned-pinned, uniform load    | 2.4 %  | 0.91 % | 0.24 % | 0.06 % |
    | clamped-clamped, uniform load  | 3.3 %  | 1.5 %  | 0.65 % | 0.31 % |
    | clamped-pinned, force at 0.3 L | 10.5 % | 4.4 %  | 1.2 %  | 0.39 % |

so below L/h = :data:`DEEP_SLENDERNESS` a row of the 2D continuum measured against a beam theory may measure the
theories' difference: :func:`deep_beam_warning` says so.
"""

from __future__ import annotations

from ..core.scene import Scene
from ..core.text import apart

DEEP_SLENDERNESS = 10.0  # L/h below which beam theory and the plane-stress solid differ by more than ~1 % of max |w|


def span_slenderness(scene: Scene) -> tuple[float, str]:
    """(the shortest span between the beam's ends and its supports inside over the largest depth along it, to 12
    digits: a scaled copy decides no side of a limit; what it is: "L/h" for the whole beam, else "span/h"). A short
    span between two inner supports bends as a short beam does, however long the beam."""
    depth = max(section.depth for _, _, section, _ in scene.pieces())
    at = sorted({0.0, float(scene.length), *(float(s.position) for s in scene.supports.inner)})
    span = min(b - a for a, b in zip(at, at[1:], strict=False))
    return float(f"{span / depth:.12g}"), ("L/h" if span == scene.length else "span/h")


def deep_beam_warning(scene: Scene) -> str | None:
    """The one-line warning of a beam, or a span between its supports, shorter than :data:`DEEP_SLENDERNESS` depths
    (:func:`span_slenderness`); None otherwise."""
    ratio, what = span_slenderness(scene)
    if not ratio < DEEP_SLENDERNESS:
        return None
    of = "length / section depth" if what == "L/h" else "the shortest span between supports / section depth"
    return (
        f"{what} = {apart(ratio, DEEP_SLENDERNESS, 3)} ({of}) is below {DEEP_SLENDERNESS:g}: beam "
        "theory holds the section plane, and the plane-stress continuum differs from it within about a depth of the "
        "supports and concentrated loads, by up to 1.2 % of max |w| at L/h = 10, 4.4 % at 5, 10.5 % at 3 (measured: a "
        "force at 0.3 L of a clamped-pinned beam; uniform loads and a cantilever's tip force 0.2-3.3 %)"
    )
