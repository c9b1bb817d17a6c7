"""Support reactions of a beam solution from its end moments and statics (``info["reactions"]`` of the beam
models that do not give K u - b at held unknowns: their boundary closures, mirror or polynomial ghosts, carry
the support's force through the fictitious points, not through a held row).

Unknown reactions per end: clamped: force and moment; pinned, roller: force; guided: moment; free: none. With
at most two unknowns the two equilibrium equations (forces along z; moments about the left end, counter-
clockwise) give them exactly; otherwise the moment of each clamped or guided end is the model's bending moment
there, M = EI d(rotation)/dx (or EI w'' without a rotation; the model's own ``M`` field when it has one), by
second-order one-sided differences, and the forces follow from statics. Sign convention as exact-eb:
force +z on the beam, moment counter-clockwise on the beam (moment_left = -M(0), moment_right = M(L), M sagging
positive)."""

from __future__ import annotations

import numpy as np

from .scene import Distributed, PointForce, PointMoment, Scene

_FORCE = {"clamped": True, "pinned": True, "roller": True, "guided": False, "free": False}
_MOMENT = {"clamped": True, "pinned": False, "roller": False, "guided": True, "free": False}


_GX, _GW = np.polynomial.legendre.leggauss(24)


def load_resultants(scene: Scene) -> tuple[float, float]:
    """(total transverse load, its counter-clockwise moment about x = 0) of the scene's loads."""
    gx, gw = _GX, _GW
    P = Mo = 0.0
    for load in scene.loads:
        if isinstance(load, PointForce):
            P += load.value
            Mo += load.value * load.position
        elif isinstance(load, PointMoment):
            Mo += load.value
        elif isinstance(load, Distributed):
            a, b = scene.span(load)
            xq = (a + b) / 2 + (b - a) / 2 * gx
            q = load.value * scene.load_shape(load, xq)
            P += float(np.sum(gw * q)) * (b - a) / 2
            Mo += float(np.sum(gw * q * xq)) * (b - a) / 2
    return P, Mo


def end_moments(scene: Scene, x: np.ndarray, w: np.ndarray, rotation, M=None) -> tuple[float, float]:
    """Sagging bending moment at x = 0 and x = L of the solution."""
    if M is not None:
        return float(M[0]), float(M[-1])
    slope = rotation if rotation is not None else np.gradient(w, x, edge_order=2)
    curv = np.gradient(slope, x, edge_order=2)
    return scene.EI * float(curv[0]), scene.EI * float(curv[-1])


def equilibrium_reactions(scene: Scene, x: np.ndarray, w: np.ndarray, rotation=None, M=None) -> dict:
    """{force_left, moment_left, force_right, moment_right, method} (module docstring)."""
    left, right = scene.supports.left, scene.supports.right
    L = scene.length
    P, Mo = load_resultants(scene)
    m0, mL = end_moments(scene, x, w, rotation, M)
    mom = {"left": -m0 if _MOMENT[left] else 0.0, "right": mL if _MOMENT[right] else 0.0}
    fl, fr = _FORCE[left], _FORCE[right]
    # forces: fl_v + fr_v + P = 0;  mom_l + mom_r + fr_v L + Mo = 0 (counter-clockwise about x = 0)
    if fl and fr:
        f_right = -(mom["left"] + mom["right"] + Mo) / L
        f_left = -P - f_right
    elif fl or fr:  # one end carries the force; a held moment there or at the other end from statics
        f_left, f_right = (-P, 0.0) if fl else (0.0, -P)
        rest = -Mo - f_right * L  # = mom_left + mom_right
        if _MOMENT[left] and _MOMENT[right]:  # clamped-guided: the clamp's moment from the model, the other's statics
            if fl:
                mom["right"] = rest - mom["left"]
            else:
                mom["left"] = rest - mom["right"]
        elif _MOMENT[left]:
            mom["left"] = rest
        elif _MOMENT[right]:
            mom["right"] = rest
    else:  # no force anywhere: a guided pair is a mechanism (rejected before solving)
        f_left = f_right = 0.0
    out = {"force_left": f_left, "moment_left": mom["left"], "force_right": f_right, "moment_right": mom["right"]}
    if fl + fr + _MOMENT[left] + _MOMENT[right] > 2:  # statically indeterminate: the model's end moment used
        out["method"] = (
            "statics with the model's end moment "
            + ("(its M field)" if M is not None else "EI d(rotation)/dx by one-sided differences")
            + " at the clamped/guided end(s)"
        )
    else:
        out["method"] = "statics (statically determinate supports)"
    return out
