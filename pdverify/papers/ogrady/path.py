"""Bond pairs that yield and break along a load path (O'Grady & Foster 2014, Eq. 7 and 8, §3.2), on the pair form
(:mod:`.pairs`, :mod:`.general`) with small rotations.

A pair deviates from straight by phi = (D w) (the paper's theta read as the deviation pi - theta, which is what
its critical angle bounds). Its force is f = a (phi - phi^p), a the pair's stiffness and phi^p its plastic offset:

* elastic-perfectly plastic (Eq. 7): |f| <= a phi_y, phi_y = delta eps_y / c (the critical angle 2 delta eps_c / t,
  c = t / 2 the extreme fibre's distance): the longest pairs yield with the extreme fibre. A pair at its cap flows:
  at the end of a step phi^p = phi - phi_y sign(f) (the paper's "plastic deformation ... applied as an offset"), so
  that it unloads elastically;
* brittle (Eq. 8): a pair whose deviation reaches phi_f = delta eps_f / c breaks for good (omega -> 0): the most
  deformed pair first, then the step is solved again, until no unbroken pair is past its angle (§3.2). Pairs equally
  deformed to round-off (mirror images) break together.

Each step is the load factor's equilibrium: the pairs at their cap carry their capped force, the others their
elastic one (:func:`.mixed.solve_mixed`), and the set at the cap is updated until it repeats (Newton on the
piecewise-linear law: exact once the set is right). A step whose set does not settle is cut back (halved) up to
``CUTS`` times; a step that still fails, or a singular system (a mechanism: a hinge, or broken pairs that free a
point), stops the path with one line and keeps the steps so far. Arrays in, arrays out; no loops over pairs.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ...core.errors import InputError, SolveError
from ...core.loading import Loading
from ...core.scene import Scene
from .calibration import horizon_length
from .conditions import conditions, nodal_loads
from .general import eliminate, reactions
from .pairs import Pairs
from .weights import shape_factors

CUTS = 8  # halvings of a step before the path stops
ACTIVE_ITERATIONS = 30  # updates of the set of pairs at their cap within one step
TIE = 1e-9  # pairs within this relative distance of the most deformed break together (mirror images)


def critical_angles(scene: Scene, pairs: Pairs, params: dict, law: str) -> np.ndarray:
    """The critical angle of each pair for ``law`` (``yield_stress`` or ``failure_strain``): delta eps_c / c of the
    section and material at the pair's centre (Eq. 7: 2 delta eps_c / t); inf where the material has no such law."""
    delta = horizon_length(params["horizon"], pairs.dx, params["variant"])
    x = pairs.centre * pairs.dx
    out = np.full(len(x), np.inf)
    for i, (a, _, sec, mat) in enumerate(scene.pieces()):
        value = getattr(mat, law)
        on = x >= a if i else np.ones(len(x), bool)
        if value is None:
            out[on] = np.inf
            continue
        prof = sec.profile
        own = bool(scene.segments) and scene.segments[i].section is not None
        where = f"segments[{i}].section" if own else "section"  # a segment without one takes the scene's
        if prof is None:
            raise InputError(
                f"{where}: material.{law} needs the section's shape (its extreme fibre sets the pairs' critical "
                "angle, Eq. 7); give width and height or a shape"
            )
        if not prof.symmetric:
            raise InputError(
                f"{where}: material.{law} with a section not symmetric about its centroid: the bond pairs keep the "
                "neutral axis at the centroid, which yielding moves; give a symmetric section"
            )
        eps = value / mat.E if law == "yield_stress" else value
        out[on] = delta * eps / prof.extreme_fibre
    return out


@dataclass
class PairState:
    """The pairs' history: plastic offsets ``offset`` (phi^p), ``capped`` (at their cap now) with ``sign``,
    ``yielded`` (ever at their cap), ``broken`` (for good)."""

    offset: np.ndarray
    capped: np.ndarray
    sign: np.ndarray
    yielded: np.ndarray
    broken: np.ndarray

    @classmethod
    def fresh(cls, P: int) -> PairState:
        z = np.zeros(P, bool)
        return cls(np.zeros(P), z.copy(), np.zeros(P), z.copy(), z.copy())

    def copy(self) -> PairState:
        return PairState(*(np.copy(v) for v in (self.offset, self.capped, self.sign, self.yielded, self.broken)))


class Unsettled(Exception):
    """The set of pairs at their cap did not settle within a step (the step is cut back)."""


@dataclass
class PathProblem:
    """What every step of one scene shares: the pairs, critical angles ``phi_y`` / ``phi_f`` (inf: no such law),
    the unit nodal loads ``F1`` and the scene (its prescribed deflections scale with the factor)."""

    scene: Scene
    pairs: Pairs
    phi_y: np.ndarray
    phi_f: np.ndarray
    F1: np.ndarray
    what: str

    def equilibrium(self, factor: float, state: PairState):
        """(w, f, cond, elim, state'): the equilibrium at ``factor`` from ``state`` (the start of the step): the set
        at the cap iterated until it repeats. Raises :class:`Unsettled` or SolveError (a mechanism)."""
        pairs, a = self.pairs, self.pairs.stiffness
        n, dx = pairs.n, pairs.dx
        cond = conditions(self.scene, n, dx, factor)
        elim = eliminate(cond.rows, cond.values, n, self.what)
        F = factor * self.F1
        cap = a * self.phi_y
        capped, sign = state.capped & ~state.broken, state.sign.copy()
        seen = set()
        for _ in range(ACTIVE_ITERATIONS):
            elastic = ~capped & ~state.broken
            fixed = np.where(capped, sign * cap, 0.0)
            w, info = solve_state(pairs, elim, cond.springs, F, self.what, elastic, fixed, state.offset)
            trial = a * (pairs.D @ w - state.offset)
            over = ~state.broken & (np.abs(trial) > cap * (1 + TIE))
            back = capped & (sign * trial < cap * (1 - TIE))  # a capped pair whose elastic force is below its cap
            new = (capped & ~back) | over
            sign = np.where(over, np.sign(trial), sign)
            key = np.flatnonzero(new).tobytes()
            if np.array_equal(new, capped):
                out = state.copy()
                out.capped, out.sign = capped, np.where(capped, sign, 0.0)
                phi = pairs.D @ w
                out.offset = np.where(capped, phi - sign * self.phi_y, state.offset)
                out.yielded = state.yielded | capped
                f = np.where(state.broken, 0.0, np.where(capped, sign * cap, a * (phi - state.offset)))
                return w, f, cond, elim, out, info
            if key in seen:
                break
            seen.add(key)
            capped = new
        raise Unsettled(f"the pairs at their cap did not settle in {ACTIVE_ITERATIONS} updates")

    def step(self, factor: float, state: PairState):
        """The equilibrium at ``factor`` with brittle pairs broken, the most deformed first (§3.2)."""
        while True:
            w, f, cond, elim, new, info = self.equilibrium(factor, state)
            if not np.isfinite(self.phi_f).any():
                return w, f, cond, elim, new, info
            ratio = np.where(new.broken, 0.0, np.abs(self.pairs.D @ w) / self.phi_f)
            top = ratio.max()
            if top <= 1.0:
                return w, f, cond, elim, new, info
            state = state.copy()
            state.broken |= ratio >= top * (1 - TIE)
            state.capped &= ~state.broken


def solve_state(pairs: Pairs, elim, Ks, F, what: str, elastic, fixed, offset):
    """(w, info): the equilibrium D^T f(w) + K_s w = F with f = a (D w - phi^p) on the ``elastic`` pairs and
    ``fixed`` on the others, w = T z + w0. Newton on the reduced stiffness T^T (D^T A_e D + K_s) T (one sparse LU,
    natural order: the band) with the residual from the pair forces (which rounds like a second difference, not
    like the fourth differences of the assembled matrix): two or three corrections reach it. A singular matrix, or
    corrections that do not settle (a load doing work on a mechanism has no equilibrium) raise SolveError."""
    D, T, w0, a = pairs.D, elim.T, elim.w0, pairs.stiffness
    ae = np.where(elastic, a, 0.0)
    Kr = (T.T @ ((D.T @ sp.diags(ae) @ D) + Ks) @ T).tocsc()
    d = Kr.diagonal()
    if np.any(d <= 0):
        raise SolveError(f"{what}: a point no pair or support holds (a mechanism)")
    s = 1.0 / np.sqrt(d)
    S = sp.diags(s)
    try:
        lu = spla.splu((S @ Kr @ S).tocsc(), permc_spec="NATURAL", diag_pivot_thresh=0.0)
    except RuntimeError as exc:
        raise SolveError(f"{what}: the stiffness is singular (a mechanism): {exc}") from None

    def residual(w):
        f = np.where(elastic, a * (D @ w - offset), fixed)
        return T.T @ (F - D.T @ f - Ks @ w)

    z = np.zeros(T.shape[1])
    w = w0.copy()
    sweeps = []
    for _ in range(8):
        dz = s * lu.solve(s * residual(w))
        z += dz
        w = T @ z + w0
        sweeps.append(float(np.abs(dz).max() / max(np.abs(z).max(), 1e-300)))
        if sweeps[-1] <= 1e-13:
            break
    if not np.all(np.isfinite(w)) or sweeps[-1] > 1e-6:
        raise SolveError(f"{what}: the equilibrium does not converge (corrections {sweeps}): a mechanism")
    return w, {"corrections": sweeps}


def node_health(pairs: Pairs, state: PairState) -> np.ndarray:
    """The fraction of each point's pairs (centred there) that never passed their critical angle (§3.2, Fig. 9)."""
    total = np.bincount(pairs.centre, minlength=pairs.n).astype(float)
    bad = np.bincount(pairs.centre, weights=(state.broken | state.yielded).astype(float), minlength=pairs.n)
    return np.where(total > 0, 1.0 - bad / np.where(total > 0, total, 1.0), 1.0)


def run_path(problem: PathProblem, factors: np.ndarray):
    """(steps, last, stop): one record per converged step (factor, w, f, reactions, counts, health), the last
    state and the line saying why the path stopped early (None when it ran to its end)."""
    pairs = problem.pairs
    state = PairState.fresh(len(pairs.centre))
    steps, stop = [], None
    lam = factors[0]
    targets = list(factors[1:])
    if lam == 0.0:
        steps.append(_record(problem, 0.0, np.zeros(pairs.n), np.zeros(len(pairs.centre)), {}, state))
    else:
        targets.insert(0, lam)
        lam = 0.0
    for target in targets:
        cut, t = 0, target
        while True:
            try:
                w, f, cond, elim, new, _ = problem.step(t, state)
            except (Unsettled, SolveError) as exc:
                if cut >= CUTS:
                    kind = "a mechanism" if isinstance(exc, SolveError) else "no equilibrium"
                    stop = (
                        f"the path stops at load factor {lam:.6g} (the step to {t:.6g} reaches {kind}: collapse, "
                        f"{int(state.yielded.sum())} pairs yielded, {int(state.broken.sum())} broken); the steps "
                        "so far are kept"
                    )
                    return steps, state, stop
                cut += 1
                t = lam + 0.5 * (t - lam)
                continue
            g = pairs.D.T @ f + cond.springs @ w
            F = t * problem.F1
            steps.append(_record(problem, t, w, f, reactions(cond, elim, g - F, w), new, cut))
            state, lam = new, t
            if t == target:
                break
            cut, t = 0, target
    return steps, state, stop


def _record(problem: PathProblem, factor, w, f, reaction, state: PairState, cuts: int = 0) -> dict:
    return {
        "factor": float(factor),
        "w": np.asarray(w, float),
        "f": np.asarray(f, float),
        "reactions": {k: float(v) for k, v in reaction.items()},
        "yielded": int(state.yielded.sum()),
        "at_cap": int(state.capped.sum()),
        "broken": int(state.broken.sum()),
        "health": node_health(problem.pairs, state),
        "cut_back": int(cuts),
    }


def path_problem(scene: Scene, params: dict, pairs: Pairs, what: str) -> PathProblem:
    """The :class:`PathProblem` of ``scene`` on ``pairs``."""
    n, dx = pairs.n, pairs.dx
    phi_y = critical_angles(scene, pairs, params, "yield_stress")
    phi_f = critical_angles(scene, pairs, params, "failure_strain")
    return PathProblem(scene, pairs, phi_y, phi_f, nodal_loads(scene, n, dx), what)


def follows_path(scene: Scene) -> bool:
    """True when ``scene`` asks for a load path: a ``[loading]`` table, a yield stress or a failure strain."""
    mats = [scene.material] + [g.material for g in scene.segments if g.material is not None]
    return scene.loading is not None or any(m.yield_stress or m.failure_strain for m in mats)


def solve_path(scene: Scene, params: dict, pairs: Pairs, what: str):
    """(w, f, path, info) of ``scene``'s load path (``[loading]``, default [0, 1] in 10 steps): the last step's
    deflection and pair forces, one JSON-ready entry per step and the path's info (stop line, counts, steps)."""
    problem = path_problem(scene, params, pairs, what)
    factors = (scene.loading or Loading()).path()
    steps, state, stop = run_path(problem, factors)
    if len(steps) < 2 and stop is not None:
        raise SolveError(f"{what}: {stop.replace('; the steps so far are kept', '')}")
    last = steps[-1]
    path = [{k: v for k, v in s.items() if k != "f"} for s in steps]
    info = {
        "load_path": {
            "factors": [float(v) for v in (scene.loading or Loading()).factors],
            "steps": len(steps),
            "cut_backs": int(sum(s["cut_back"] > 0 for s in steps)),
            "completed": stop is None,
            "last_factor": last["factor"],
            "yielded_pairs": last["yielded"],
            "broken_pairs": last["broken"],
            "pairs": int(len(pairs.centre)),
        },
        "reactions": last["reactions"],
    }
    if stop is not None:
        info.setdefault("warnings", []).append(stop)
    return last["w"], last["f"], path, info, state


def plastic_warnings(scene: Scene, params: dict, dx: float) -> list[str]:
    """The shape factor Mp / My of the pairs' moment-curvature law beside the fibre theory's, when they differ by
    more than 1 % (Eq. 6 weighs the fibre at y by b y², the fibre theory by b y; :mod:`.weights`)."""
    mat = scene.material
    if mat.yield_stress is None or scene.segments or params["variant"] == "continuous-alpha":
        return []
    prof = scene.section.profile
    got = shape_factors(prof, params["weight"], params["horizon"], dx, params["variant"])
    if abs(got["pd"] / got["fibre"] - 1.0) <= 0.01:
        return []
    fibre = shape_factors(prof, "fibre", params["horizon"], dx, params["variant"])["pd"]
    if params["weight"] != "fibre" and abs(fibre / got["fibre"] - 1.0) <= 0.01:
        fix = f"-o weight=fibre reproduces it ({fibre:.4g})"
    else:
        fix = f"more members per horizon bring the fibre weight's ({fibre:.4g} here) to it, at second order"
    return [
        f"weight = {params['weight']}, horizon = {params['horizon']:g}: the pairs' shape factor Mp / My is "
        f"{got['pd']:.4g} where the fibre theory's is {got['fibre']:.4g} (the section's Z / S): past first yield "
        f"the moment-curvature law is not the beam's; {fix}"
    ]


def failure_warnings(scene: Scene, params: dict, x: np.ndarray, info: dict, health: np.ndarray) -> list[str]:
    """Past failure the beam hinges where its broken pairs are: at the peak of the curvature averaged over each
    pair's ±xi (the pair's phi, Eq. 3), which lies up to a horizon from the local theory's peak (under an off-centre
    load, towards the gentler side of the moment diagram). The hinge's position, and with it the broken beam's
    deflection, is therefore first order in the horizon, and so in the spacing at a fixed horizon factor. Where the
    hinge forms beside a prescribed deflection at a, with the nearest supports that hold the deflection at a - l and
    a + r, the broken halves are straight: a hinge Δ off a moves the deflections by about Δ (1/l + 1/r) of the
    prescribed one, which the warning gives."""
    broken = info["load_path"]["broken_pairs"]
    if not broken:
        return []
    dx = float(x[1] - x[0])
    delta = horizon_length(params["horizon"], dx, params["variant"])
    at = x[np.flatnonzero(health == health.min())]
    where = f"x = {at[0]:.6g}" + (f" ... {at[-1]:.6g}" if len(at) > 1 else "")
    text = (
        f"{broken} pairs broke (the least healthy point at {where}): the hinge forms where the curvature averaged "
        f"over the horizon peaks, up to a horizon ({delta:.3g}) from the local beam theory's peak, so past failure "
        "the deflection converges at first order in the spacing"
    )
    hinge = float(at[len(at) // 2])
    sup = scene.supports
    held = [0.0] * sup.holds_deflection_at("left") + [scene.length] * sup.holds_deflection_at("right")
    held += [s.position for s in sup.inner if s.holds_deflection]
    shown = [(i, ld) for i, ld in enumerate(scene.loads) if ld.type == "displacement"]
    if shown:
        i, ld = min(shown, key=lambda item: abs(item[1].position - hinge))
        left = [ld.position - h for h in held if h < ld.position]
        right = [h - ld.position for h in held if h > ld.position]
        shift = abs(hinge - ld.position)
        if shift > 1e-9 * dx and left and right:
            size = shift * (1.0 / min(left) + 1.0 / min(right))
            text += (
                f"; the hinge is {shift:.3g} ({shift / dx:.3g} dx) from loads[{i}]'s prescribed deflection at "
                f"{ld.position:g}, which moves the broken beam's deflections by about {100 * size:.2g} % of it"
            )
    return [text + " (docs/models/ogrady.md, brittle failure)"]
