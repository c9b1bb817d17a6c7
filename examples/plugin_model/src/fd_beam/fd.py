"""Euler-Bernoulli beam EI w'''' = q by central finite differences on the mixed form m'' = q, w'' = m / EI
(m = EI w''): second order in the spacing h. Plain numpy/scipy on the scene as pdverify writes it in JSON
(``Scene.to_dict()``), so the plug-in (``fd_beam.FDBeam``) and the external command share it."""

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve


def bending_stiffness(scene: dict) -> float:
    s = scene["section"]
    inertia = s["inertia"] if s.get("inertia") else s["width"] * s["height"] ** 3 / 12
    return scene["material"]["youngs_modulus"] * inertia


def nodal_loads(scene: dict, x: np.ndarray):
    """q_i = (1/h) * integral of q against the hat function of node i (force: F phi_i(a), moment: C phi_i'(a))."""
    L, h, q = scene["beam"]["length"], x[1] - x[0], np.zeros(len(x))
    ends = {0: [0.0, 0.0], len(x) - 1: [0.0, 0.0]}  # end node -> [force, moment] taken by the end conditions
    for ld in scene["loads"]:
        kind, value = ld["type"], ld["value"]
        if kind in ("point_force", "point_moment") and ld["position"] in (0.0, L):
            ends[0 if ld["position"] == 0.0 else len(x) - 1][kind == "point_moment"] += value
        elif kind in ("point_force", "point_moment"):
            k = min(int(ld["position"] / h), len(x) - 2)
            t = ld["position"] / h - k
            if kind == "point_force":
                q[k : k + 2] += value * np.array([1 - t, t]) / h
            else:  # a couple on nodes k and k+1, shared as t: each the mean of the hat slopes on both sides
                j = np.clip([k - 1, k + 1, k, k + 2], 0, len(x) - 1)
                np.add.at(q, j, value * np.array([-(1 - t), 1 - t, -t, t]) / (2 * h**2))
        else:  # distributed: 3-point Gauss on each cell's loaded part
            a, b = ld.get("start") or 0.0, L if ld.get("end") is None else ld["end"]
            lo, hi = np.clip(x[:-1], a, b), np.clip(x[1:], a, b)
            for g, wg in ((-np.sqrt(0.6), 5 / 18), (0.0, 8 / 18), (np.sqrt(0.6), 5 / 18)):
                xg = (lo + hi) / 2 + g * (hi - lo) / 2
                f = value * (np.sin(np.pi * xg / L) if ld.get("shape") == "sine" else 1.0) * wg * (hi - lo) / h
                q[:-1] += f * (x[1:] - xg) / h
                q[1:] += f * (xg - x[:-1]) / h
    return q, ends


def solve(scene: dict, n: int) -> dict:
    """x, w, rotation w' and moment M at n equally spaced points."""
    EI = bending_stiffness(scene)
    x = np.linspace(0.0, scene["beam"]["length"], n)
    h = x[1] - x[0]
    q, ends = nodal_loads(scene, x)
    d2 = sp.diags([1.0, -2.0, 1.0], [0, 1, 2], shape=(n - 2, n)) / h**2  # second difference at interior nodes
    zero, eye = sp.csr_matrix((n - 2, n)), sp.eye(n, format="csr")[1:-1]
    rows = [sp.hstack([zero, d2]), sp.hstack([d2, -eye / EI])]  # unknowns [w, m]: m'' = q, w'' - m/EI = 0
    rhs = [q[1:-1], np.zeros(n - 2)]
    for i, s in ((0, 1), (n - 1, -1)):  # left end (inward +1), right end (inward -1)
        value = sp.lil_matrix((1, n))
        value[0, i] = 1.0
        slope = sp.lil_matrix((1, n))
        slope[0, [i, i + s, i + 2 * s]] = np.array([-3.0, 4.0, -1.0]) * s / (2 * h)
        force, moment = ends[i]
        empty = sp.csr_matrix((1, n))
        conds = {
            "clamped": [(value, empty, 0.0), (slope, empty, 0.0)],
            "pinned": [(value, empty, 0.0), (empty, value, -s * moment)],
            "roller": [(value, empty, 0.0), (empty, value, -s * moment)],  # no axial unknown: as pinned
            "free": [(empty, value, -s * moment), (empty, slope, s * force)],
            "guided": [(slope, empty, 0.0), (empty, slope, s * force)],
        }[scene["supports"]["left" if i == 0 else "right"]]
        for cw, cm, r in conds:
            rows.append(sp.hstack([cw, cm]))
            rhs.append([r])
    sol = spsolve(sp.vstack(rows).tocsc(), np.concatenate(rhs))
    w, m = sol[:n], sol[n:]
    return {"x": x, "w": w, "rotation": np.gradient(w, h, edge_order=2), "M": m}
