"""One factorisation per operator: the LU of a matrix met again (another load on the same beam, grid and
supports) is taken from a small cache instead of being made again.

The key is a digest (BLAKE2b, 128 bits) of the matrix's canonical CSR arrays, its scaling and the solver's
parameters, so two systems share a factorisation only when their matrices are the same to the bit; a solve from
a shared factorisation is then the same to the bit as one made apart (the same factors, the same substitutions).
The cache holds at most ``ENTRIES`` factorisations of at most ``MAX_UNKNOWNS`` unknowns each, per process.
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict

import numpy as np

ENTRIES = 16  # factorisations kept: a verification suite's scenes on one grid and supports differ in their loads
MAX_UNKNOWNS = 20_000  # larger systems are rarely solved twice; their factors are not kept
_cache: OrderedDict[str, object] = OrderedDict()
stats = {"made": 0, "shared": 0}


def digest(*arrays, params: tuple = ()) -> str:
    """The key of a system: its arrays' bytes, dtypes and shapes, and ``params``."""
    h = hashlib.blake2b(digest_size=16)
    for a in arrays:
        a = np.ascontiguousarray(a)
        h.update(f"{a.dtype.str}{a.shape}".encode())
        h.update(a.tobytes())
    h.update(repr(params).encode())
    return h.hexdigest()


def factorised(key: str, n: int, make):
    """(factorisation, shared): the one kept under ``key``, else ``make()`` (kept when ``n`` is at most
    ``MAX_UNKNOWNS``). ``shared`` says whether it was kept from an earlier solve."""
    if key in _cache:
        _cache.move_to_end(key)
        stats["shared"] += 1
        return _cache[key], True
    value = make()
    stats["made"] += 1
    if n <= MAX_UNKNOWNS:
        _cache[key] = value
        while len(_cache) > ENTRIES:
            _cache.popitem(last=False)
    return value, False


def clear() -> None:
    """Forget every kept factorisation (a test that solves apart)."""
    _cache.clear()
    stats.update(made=0, shared=0)
