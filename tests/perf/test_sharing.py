"""The factorisation-sharing measurement of ``pdverify bench --sharing`` (pdverify/apps/sharing.py): sharing
changes no number of a verification suite and factorises each operator once."""

import pytest

from pdverify.apps.sharing import sharing_gain


@pytest.mark.slow
def test_sharing_changes_no_number_and_factorises_each_operator_once():
    r = sharing_gain("fem-eb")
    assert r["same"], r
    assert r["factorisations_apart"] == r["cases"], r  # without the cache, one factorisation per case
    # with it, one per distinct operator: the suite's loads share the beam, grid and supports of their scene
    assert r["factorisations_shared"] < r["cases"] / 3, r
