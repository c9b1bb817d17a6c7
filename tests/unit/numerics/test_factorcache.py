"""One factorisation per operator (pdverify/numerics/factorcache.py): a system whose matrix was factorised before
takes the kept factors, and its solution, bound and condition estimate are the same to the bit as a solve made
apart."""

import numpy as np
import pytest
import scipy.sparse as sp

from pdverify.numerics import factorcache
from pdverify.numerics.linalg import solve_linear
from pdverify.registry import run


def _operator(n):
    main = np.full(n, 6.0)
    main[[0, -1]] = 7.0
    return sp.diags(
        [np.ones(n - 2), np.full(n - 1, -4.0), main, np.full(n - 1, -4.0), np.ones(n - 2)], [-2, -1, 0, 1, 2]
    )


@pytest.mark.parametrize("n", [60, 500])  # the sparse-converted small path and the banded LU with its estimate
def test_a_shared_factorisation_gives_the_same_bits(n):
    K = _operator(n)
    loads = [np.sin(np.linspace(0, 3, n)), np.linspace(-1, 1, n) ** 3]
    factorcache.clear()
    together = [solve_linear(K, b, "test") for b in loads]
    assert [info["factorisation_shared"] for _, info in together] == [False, True]
    assert together[0][1]["factorisation"] == together[1][1]["factorisation"]
    for (u, info), b in zip(together, loads):
        factorcache.clear()
        u_apart, info_apart = solve_linear(K, b, "test")
        assert np.array_equal(u, u_apart)
        for key in ("error_bound", "residual", "cond"):
            assert info[key] == info_apart[key] or (np.isnan(info[key]) and np.isnan(info_apart[key]))


def test_a_different_matrix_is_never_shared():
    """One bit of one entry changed: another key, another factorisation."""
    K = _operator(200).tocsr()
    b = np.ones(200)
    factorcache.clear()
    solve_linear(K, b, "test")
    K2 = K.copy()
    K2.data[7] = np.nextafter(K2.data[7], np.inf)
    _, info = solve_linear(K2, b, "test")
    assert not info["factorisation_shared"]


def test_a_model_on_two_loads_shares_and_matches(make_scene):
    """pd-eb on one beam under two loads: the second solve takes the first's factors; both deflections equal the
    ones solved apart, to the bit."""
    scenes = [
        make_scene("clamped", "pinned", [{"type": "point_force", "position": 0.3, "value": -50.0}]),
        make_scene("clamped", "pinned", [{"type": "distributed", "value": -20.0}]),
    ]
    factorcache.clear()
    together = [run(s, "pd-eb", points=101) for s in scenes]
    assert together[1].info["factorisation_shared"]
    for r, s in zip(together, scenes):
        factorcache.clear()
        assert np.array_equal(r.w, run(s, "pd-eb", points=101).w)


def test_a_derived_object_is_made_once_beside_its_factorisation_and_counted_in_the_budget(monkeypatch):
    """The rounding layout of a matrix met again (the round-off bound's entries grouped by significand) is kept with
    its factors; without a kept factorisation it is made each time; its bytes count, so the budget evicts it."""
    factorcache.clear()
    made = []

    def make():
        made.append(1)
        return "layout", 100

    assert factorcache.derived("nothing kept", "layout", make) == "layout" and len(made) == 1
    factorcache.derived("nothing kept", "layout", make)
    assert len(made) == 2
    factorcache.factorised("k", lambda: ("lu", 10))
    assert [factorcache.derived("k", "layout", make) for _ in range(3)] == ["layout"] * 3 and len(made) == 3
    monkeypatch.setattr(factorcache, "BUDGET_BYTES", 50)
    factorcache.factorised("k2", lambda: ("lu2", 10))  # k's 110 bytes are over the budget now: evicted
    assert factorcache.factorised("k", lambda: ("lu again", 10)) == ("lu again", False)
    factorcache.clear()
