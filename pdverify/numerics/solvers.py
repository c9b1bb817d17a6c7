"""The linear solver of a static model: banded (direct) LU or the large-horizon Krylov path, and the choice.

``solve(K, b, what, solver=...)`` takes the model option ``solver`` (:data:`SOLVER`):

* ``"banded"``: :func:`~pdverify.numerics.linalg.solve_linear`: LAPACK's band LU of an operator assembled as a band
  (:class:`~pdverify.numerics.band.Band`) whatever its width; an operator assembled otherwise, or reached as the
  fallback of ``"auto"``, by band LU up to the model's bandwidth limit and sparse LU past it;
* ``"krylov"``: :func:`~pdverify.numerics.krylov.solve_krylov` whenever the operator is a band that is Toeplitz
  away from its ends (:func:`~pdverify.numerics.krylov.plan`); one line naming the reason otherwise;
* ``"auto"`` (default): the Krylov path for a band of half-width at least ``KRYLOV_MIN_HALF_BANDWIDTH`` with
  ``KRYLOV_MIN_UNKNOWNS`` unknowns or more, Toeplitz away from its ends and held at both ends, else banded. The
  choice depends on the matrix alone (deterministic); ``info["solver_choice"]`` says which and why. Should an
  inner iteration fail to converge, the banded solve is made instead and the result says so.
"""

from __future__ import annotations

import numpy as np

from ..core.contract import Option
from ..core.errors import InputError
from .band import Band
from .krylov import SOLVERS, plan, solve_krylov
from .linalg import SMALL, solve_linear

SOLVER = Option(
    "solver",
    str,
    "auto",
    "linear solver: auto (Krylov with a sine-transform preconditioner for wide bands on uniform grids held at "
    "both ends, else banded LU) | banded | krylov (docs/solvers.md)",
    choices=SOLVERS,
)


def solve(
    K,
    b: np.ndarray,
    what: str = "system",
    solver: str = "auto",
    condition: bool | None = None,
    watch=None,
    magnitude=None,
    **banded,
) -> tuple[np.ndarray, dict]:
    """Solve K u = b with the solver ``solver`` chose (module docstring). ``condition``, ``watch``, ``magnitude``:
    as for :func:`~pdverify.numerics.linalg.solve_linear`, which receives ``banded`` too."""
    if solver not in SOLVERS:
        raise InputError(f"solver = {solver!r}: give one of {', '.join(SOLVERS)}")
    choice = "banded: asked for"
    if solver != "banded":
        pl, why = plan(K, forced=solver == "krylov")
        if pl is None and solver == "krylov":
            raise InputError(f"solver = krylov: {why}; use solver = auto or banded")
        if pl is not None:
            n = K.n
            cond = condition if condition is not None else n <= SMALL
            u, info = solve_krylov(K, b, pl, what, watch, magnitude, condition=cond)
            info["solver_choice"] = f"krylov: {why}" if solver == "auto" else "krylov: asked for"
            if solver == "krylov" or info["krylov_converged"]:
                return u, info
            choice = "banded: the Krylov iteration did not converge"
        else:
            choice = f"banded: {why}"
    if solver == "banded" and isinstance(K, Band):  # asked for: LAPACK's band LU whatever the width
        banded["banded_max"] = max(banded.get("banded_max", 0), K.lower, K.upper)
    u, info = solve_linear(K, b, what, condition=condition, watch=watch, magnitude=magnitude, **banded)
    info["solver_choice"] = choice
    return u, info
