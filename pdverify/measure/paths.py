"""A load path reduced to one curve: the load factor against the deflection at one point, the point where the
deflection is largest at the path's largest load factor (mid-span of O'Grady & Foster's simply supported beams,
Figs. 6-7; the tip of a cantilever). Every model's path gives the same kind of curve, so the report draws them over
each other."""

from __future__ import annotations

import numpy as np

DISPLACED = "force_displacement_0"  # the reaction of a prescribed deflection: the force that holds it


def peak_history(x: np.ndarray, steps: list[dict]) -> dict | None:
    """{"x": the point, "factor": each step's load factor, "w": each step's deflection there} of a path whose steps
    carry ``factor`` and ``w`` at the points ``x`` (and "force": the force on the beam of a prescribed deflection,
    where the steps give it); None when the steps carry no deflection at those points."""
    x = np.asarray(x, float)
    if not steps or any(np.shape(s.get("w")) != x.shape for s in steps):
        return None
    factors = np.array([float(s["factor"]) for s in steps])
    W = np.array([np.asarray(s["w"], float) for s in steps])
    peak = int(np.argmax(np.abs(factors)))  # the first step at the largest factor
    i = int(np.argmax(np.abs(W[peak])))
    out = {"x": float(x[i]), "factor": factors, "w": W[:, i].copy()}
    if any(DISPLACED in s.get("reactions", {}) for s in steps):  # deflection control: the force it takes
        out["force"] = np.array([_held_force(s) for s in steps])
    return out


def _held_force(step: dict) -> float:
    """The force of a step's prescribed deflection: 0 at a zero factor where the step solved nothing, else NaN where
    the step does not give it."""
    got = step.get("reactions", {}).get(DISPLACED)
    if got is None:
        return 0.0 if float(step["factor"]) == 0.0 else float("nan")
    return float(got)
