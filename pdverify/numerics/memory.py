"""The memory a banded factorisation needs against what the machine has: refused before the allocation, with the
estimate (the run's peak resident set, measured: docs/cli.md, the memory guard)."""

from __future__ import annotations

from ..core.errors import SolveError

BYTES_PER_BAND_ENTRY = 6 * 8  # float64 entries, x6 the banded matrix for the copies and workspaces of a run


def available_bytes() -> int | None:
    """The memory this process may still take: the least of the machine's MemAvailable (/proc/meminfo), the room left
    under its control group's limit (cgroup v2 memory.max less memory.current, v1 memory.limit_in_bytes less
    memory.usage_in_bytes) and under its address-space limit (``ulimit -v``: RLIMIT_AS less VmSize); None when none
    is known (not Linux: then nothing is refused)."""
    known = [v for v in (_meminfo(), _cgroup_room(), _address_space_room()) if v is not None]
    return min(known) if known else None


def _number(path: str) -> int | None:
    """The integer a /proc or /sys file holds (None: absent, unreadable or "max")."""
    try:
        with open(path) as fh:
            return int(fh.read().split()[0])
    except (OSError, ValueError, IndexError):
        return None


def _meminfo() -> int | None:
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        return None
    return None


UNLIMITED = 1 << 60  # a cgroup v1 limit this large is "no limit" (the kernel writes 2^63 rounded to pages)


def _cgroup_room() -> int | None:
    """Limit less usage of the process's memory control group: its own folder under /sys/fs/cgroup, or the root of a
    container's view; None when no limit is set."""
    try:
        with open("/proc/self/cgroup") as fh:
            lines = [line.rstrip("\n").split(":", 2) for line in fh]
    except OSError:
        return None
    for _, controllers, path in (p for p in lines if len(p) == 3):
        if controllers == "":  # v2
            pairs = [(f"/sys/fs/cgroup{d}/memory.max", f"/sys/fs/cgroup{d}/memory.current") for d in (path, "")]
        elif "memory" in controllers.split(","):  # v1
            root = "/sys/fs/cgroup/memory"
            pairs = [(f"{root}{d}/memory.limit_in_bytes", f"{root}{d}/memory.usage_in_bytes") for d in (path, "")]
        else:
            continue
        for limit_file, usage_file in pairs:
            limit, usage = _number(limit_file), _number(usage_file)
            if limit is not None and usage is not None and limit < UNLIMITED:
                return max(limit - usage, 0)
    return None


def _address_space_room() -> int | None:
    """RLIMIT_AS (``ulimit -v``) less the process's virtual size; None when unlimited."""
    try:
        import resource

        soft = resource.getrlimit(resource.RLIMIT_AS)[0]
        if soft == resource.RLIM_INFINITY:
            return None
        with open("/proc/self/status") as fh:
            size = next(int(line.split()[1]) * 1024 for line in fh if line.startswith("VmSize:"))
        return max(soft - size, 0)
    except (ImportError, OSError, ValueError, StopIteration):
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
