"""Numbers in messages."""

from __future__ import annotations


def apart(value: float, limit: float, digits: int = 2) -> str:
    """``value`` with the fewest significant digits, at least ``digits``, that tell it from ``limit`` (a bound
    just past its limit reads "1.0000001e-06", not "1e-06"); repr-exact when no rounding does."""
    return next(
        (f"{value:.{d}g}" for d in range(digits, 18) if float(f"{value:.{d}g}") != float(f"{limit:.{d}g}")),
        repr(value),
    )
