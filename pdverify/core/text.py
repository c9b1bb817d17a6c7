"""Numbers in messages."""

from __future__ import annotations

import math


def apart(value: float, limit: float, digits: int = 2) -> str:
    """``value`` with the fewest significant digits, at least ``digits``, that tell it from ``limit`` (a bound
    just past its limit reads "1.0000001e-06", not "1e-06"); repr-exact when no rounding does."""
    return next(
        (f"{value:.{d}g}" for d in range(digits, 18) if float(f"{value:.{d}g}") != float(f"{limit:.{d}g}")),
        repr(value),
    )


def counted(value, noun: str, spec: str = "g") -> str:
    """``value`` formatted with ``spec`` and ``noun``, plural unless it reads 1: "1 spacing", "2.5 spacings"."""
    shown = f"{value:{spec}}"
    return f"{shown} {noun}" if shown == "1" else f"{shown} {noun}s"


def spacings(value, spec: str = ".3g") -> str:
    """A distance in spacings of the grid: "1 spacing", "2.5 spacings"."""
    return counted(value, "spacing", spec)


def listed(values) -> str:
    """Positions or values in a message, each with ``g`` formatting: "0.02, 0.1"."""
    return ", ".join(f"{v:g}" for v in values)


PRACTICAL_POINTS = 10**8  # a grid past this many points does not fit a workstation's memory for any model


def rounded_up(value: float, digits: int = 2) -> str:
    """``value`` to ``digits`` significant digits, rounded up (an upper estimate printed is not below itself)."""
    if not (value > 0 and math.isfinite(value)):
        return f"{value:.{digits}g}"
    step = 10.0 ** (math.floor(math.log10(value)) - digits + 1)
    return f"{math.ceil(value / step * (1 - 1e-12)) * step:.{digits}g}"


def rounded_down(value: float, digits: int = 3) -> str:
    """``value`` to ``digits`` significant digits, rounded down (a limit "below X" printed is not above itself, and a
    mirror image's value a rounding lower reads the same)."""
    if not (value > 0 and math.isfinite(value)):
        return f"{value:.{digits}g}"
    step = 10.0 ** (math.floor(math.log10(value)) - digits + 1)
    return f"{math.floor(value / step * (1 + 1e-12)) * step:.{digits}g}"


def more_points(points: float) -> str:
    """The advice "use at least N points" (N = ceil(points)), or, past :data:`PRACTICAL_POINTS`, that no practical grid
    does it (a point load 1e-15 m beside a support asked for 7,205,759,403,792,795 points)."""
    n = int(min(math.ceil(points), 2**63)) if math.isfinite(points) else 2**63
    if n <= PRACTICAL_POINTS:
        return f"use at least {n} points"
    return f"no practical grid does it (about {float(points):.2g} points): move the two apart or give them as one"


def close_match(word: str, choices, cutoff: float = 0.75) -> str | None:
    """The one of ``choices`` that ``word`` looks like a misspelling of (difflib's ratio at least ``cutoff``, 0.75 as
    a scene file's "did you mean"), or None."""
    import difflib

    found = difflib.get_close_matches(str(word), [str(c) for c in choices], n=1, cutoff=cutoff)
    return found[0] if found else None


PAST_RANGE = " (infinite, or typed past float64's range: 1e400 reads as inf)"  # said of an infinite number given
