"""One factorisation per operator: the LU of a matrix met again (another load on the same beam, grid and
supports) is taken from a small cache instead of being made again.

The key is a digest (BLAKE2b, 128 bits) of the matrix's canonical CSR arrays, its scaling and the solver's
parameters, so two systems share a factorisation only when their matrices are the same to the bit; a solve from
a shared factorisation is then the same to the bit as one made apart (the same factors, the same substitutions).
The cache holds at most ``ENTRIES`` factorisations per process, whose factors take at most ``BUDGET_BYTES``
together (the least recently used go first; a factorisation larger than the budget is not kept).
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict

import numpy as np

ENTRIES = 16  # factorisations kept: a verification suite's scenes on one grid and supports differ in their loads
BUDGET_BYTES = 512 * 2**20  # the factors kept, together (a 2D strip of 33,000 unknowns: ~20 MB)
_cache: OrderedDict[str, list] = OrderedDict()  # key -> [factorisation, bytes, {name: derived object}]
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


def factorised(key: str, make):
    """(factorisation, shared): the one kept under ``key``, else the first item of ``make()`` = (factorisation, the
    bytes its factors take), kept within :data:`ENTRIES` and :data:`BUDGET_BYTES`. ``shared`` says whether it was
    kept from an earlier solve."""
    if key in _cache:
        _cache.move_to_end(key)
        stats["shared"] += 1
        return _cache[key][0], True
    value, size = make()
    stats["made"] += 1
    if size <= BUDGET_BYTES:
        _cache[key] = [value, size, {}]
        _evict()
    return value, False


def derived(key: str, name: str, make):
    """An object derived from the matrix kept under ``key`` (its rounding layout, say), made once by ``make()`` =
    (object, its bytes) and kept beside the factorisation, its bytes counted in :data:`BUDGET_BYTES`; made afresh
    (and not kept) when no factorisation is kept under ``key``."""
    entry = _cache.get(key)
    if entry is None:
        return make()[0]
    if name not in entry[2]:
        value, size = make()
        entry[2][name] = value
        entry[1] += size
        _evict()
        return value
    return entry[2][name]


def _evict() -> None:
    """The least recently used entries out until :data:`ENTRIES` and :data:`BUDGET_BYTES` hold."""
    while len(_cache) > ENTRIES or sum(v[1] for v in _cache.values()) > BUDGET_BYTES:
        _cache.popitem(last=False)


def clear() -> None:
    """Forget every kept factorisation (a test that solves apart)."""
    _cache.clear()
    stats.update(made=0, shared=0)
