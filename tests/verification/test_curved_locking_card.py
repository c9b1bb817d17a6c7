"""verify's locking check sees locking on a curved axis: the suite (1.6) gives the curved beam models a clamped-free
quarter circle under a uniform load at L/h = 5 ... 10^4 against exact-curved, and the check fails pd-curved's primal
form (the paper's, which locks like (L/h)^2, docs/models/curved.md) and passes its mixed form. A straight axis does
not show it: the primal card passed locking on the straight scenes alone.

Measured at 161 particles, error in max |w|: primal 1.3e-6, 2.0e-5, 4.9e-4, 4.4e-2, 1.35 at L/h = 5, 20, 100, 10^3,
10^4; mixed 3.9e-9 at every slenderness."""

import numpy as np
import pandas as pd
import pytest

from pdverify.core.scene_file import parse_scene
from pdverify.registry import get_model, run
from pdverify.verify import checks as C
from pdverify.verify.suite import LOCKING_SLENDERNESS, plan


def test_the_curved_beam_models_get_the_curved_locking_scenes():
    sets = [m["set"] for m in plan(get_model("pd-curved")).meta.values()]
    assert sets.count("curved_locking") == len(LOCKING_SLENDERNESS)
    assert "curved_locking" not in [m["set"] for m in plan(get_model("fem-plane-stress")).meta.values()]
    assert "curved_locking" not in [m["set"] for m in plan(get_model("pd-eb")).meta.values()]


@pytest.mark.parametrize("form, verdict", [("primal", "fail"), ("mixed", "pass")])
def test_the_locking_check_fails_the_primal_form_on_a_curved_axis(form, verdict):
    p = plan(get_model("pd-curved"), options={"form": form})
    files = [f for f, m in p.meta.items() if m["set"] == "curved_locking"]
    rows = []
    for f in files:
        sc = parse_scene(p.scenes[f])
        r, e = run(sc, "pd-curved", points=161, form=form), run(sc, "exact-curved", points=161)
        err = float(np.abs(r.w - e.w).max() / np.abs(e.w).max())
        bound = r.info["error_bound"]
        status = "ok" if bound <= 1e-6 else "suspect"
        rows.append({"scene_file": f, "points": 161, "err_max": err, "status": status, "error_bound": bound})
    found = C.locking(pd.DataFrame(rows), files, p.meta)
    assert found["verdict"] == verdict, found["summary"]
