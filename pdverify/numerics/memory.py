"""The memory a banded factorisation needs against what the machine has: refused before the allocation, with the
estimate (the run's peak resident set, measured: docs/cli.md, the memory guard)."""

from __future__ import annotations

from ..core.errors import SolveError

BYTES_PER_BAND_ENTRY = 6 * 8  # float64 entries, x6 the banded matrix for the copies and workspaces of a run


def available_bytes() -> int | None:
    """MemAvailable of /proc/meminfo (Linux), else None (then nothing is refused)."""
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        return None
    return None


def check_band(unknowns: int, lower: int, upper: int, what: str, fix: str) -> None:
    """SolveError (exit 3) when a system of ``unknowns`` in a band of ``lower`` + ``upper`` + 1 diagonals would need
    more than the available memory to factorise (its LU fills the band: BYTES_PER_BAND_ENTRY a band entry); ``fix``:
    what to give instead."""
    have = available_bytes()
    need = BYTES_PER_BAND_ENTRY * unknowns * (2 * lower + upper + 1)
    if have is not None and need > have:
        raise SolveError(
            f"{what}: its system has {unknowns:,} unknowns in a band of {lower + upper + 1:,}, whose factorisation "
            f"would need about {need / 2**30:.1f} GiB; {have / 2**30:.1f} GiB is available; {fix}"
        )
