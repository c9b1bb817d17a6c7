"""A load path reduced to one curve: the load factor against the deflection at one point, the point where the
deflection is largest at the path's largest load factor (mid-span of O'Grady & Foster's simply supported beams,
Figs. 6-7; the tip of a cantilever). Every model's path gives the same kind of curve, so the report draws them over
each other."""

from __future__ import annotations

import numpy as np


def peak_history(x: np.ndarray, steps: list[dict]) -> dict | None:
    """{"x": the point, "factor": each step's load factor, "w": each step's deflection there} of a path whose steps
    carry ``factor`` and ``w`` at the points ``x``; None when the steps carry no deflection at those points."""
    x = np.asarray(x, float)
    if not steps or any(np.shape(s.get("w")) != x.shape for s in steps):
        return None
    factors = np.array([float(s["factor"]) for s in steps])
    W = np.array([np.asarray(s["w"], float) for s in steps])
    peak = int(np.argmax(np.abs(factors)))  # the first step at the largest factor
    i = int(np.argmax(np.abs(W[peak])))
    return {"x": float(x[i]), "factor": factors, "w": W[:, i].copy()}
