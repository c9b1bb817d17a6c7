"""Shared pieces of the PD beams' dynamics tests: a slender beam (L/h = 500) for natural frequencies against the
Euler-Bernoulli ones, the interior stencil's dispersion that predicts a PD operator's frequency error, and a small
cantilever under a tip step load for transients."""

import numpy as np
from helpers import scene_dict

from pdverify.core.scene_file import parse_scene
from pdverify.numerics.dispersion import stencil_branches

DENSITY = 2700.0


def slender(left, right, height=0.004, loads=(), dynamics=None):
    d = scene_dict(left, right, list(loads))
    d["section"]["height"] = height
    d["material"]["density"] = DENSITY
    if dynamics:
        d["dynamics"] = dynamics
    return parse_scene(d)


def dispersion(model, sc, params, count=5):
    """omega_h / omega - 1 of the interior row of the model's operator for the pinned-pinned wavenumbers j pi / L
    (the PD operator's own error: a nonlocal stencil's symbol falls below EI k^4 by ~ (k delta)^2)."""
    K, mass = model.eigenproblem(sc, model.resolve(sc, params))
    K, mass = K.tocsr(), np.asarray(mass)
    mid = K.shape[0] // 2
    row = K[mid].toarray().ravel()
    blocks = {o - mid: np.array([[row[o]]]) for o in np.flatnonzero(row)}
    k = np.arange(1, count + 1) * np.pi / sc.length
    dx = sc.length / (params["points"] - 1)
    w_h = stencil_branches(blocks, np.array([mass[mid]]), k * dx)[:, 0]
    return w_h / (k**2 * np.sqrt(sc.EI / (DENSITY * sc.section.A))) - 1


def tip_load(left="clamped", right="free", points=41, end_time=0.2, height=0.02, **dyn):
    return slender(
        left,
        right,
        height,
        [{"type": "point_force", "position": 2.0 if right == "free" else 1.0, "value": -100.0}],
        dict({"end_time": end_time, "probes": [1.0, 2.0]}, **dyn),
    )


def check_ledger(r, kind):
    """The ledger's kind; the scheme's discrete energy conserved to round-off: 10 eps per step (each step's update
    rounds the energy by a few eps of the stored energy) plus one evaluation's round-off, eps cond(K) =
    eps (omega_max / omega_1)^2 (u.K u of a smooth u cancels that many digits); stored energy within the work put
    in to that size plus the sampling's O((omega dt)^2) (T + U - W: measured 7.2e-7 of the work at most, asserted
    below 1e-5)."""
    i = r.info
    eps = np.finfo(float).eps
    assert i["energy_ledger"] == kind
    assert i["scheme_drift"] < 10 * eps * i["steps"] + eps * (2 / i["dt_limit"] / i["omega1"]) ** 2
    e = i["history"]["energy"]
    work = np.abs(e["load_work"]).max()
    assert np.max(e["kinetic"] + e["strain"]) <= work * (1 + 1e-6)
    assert i["energy_drift"] < 1e-5
    # the default step 0.9 x the limit, shortened to whole steps that end at end_time: by less than one step's share
    assert i["dt"] <= 0.9 * i["dt_limit"] < i["dt"] * (1 + 1 / (i["steps"] - 1))
