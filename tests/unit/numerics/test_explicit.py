"""The explicit integrator of pdverify.numerics.explicit: block mass factor, the modal run of a non-symmetric
operator, conservation of the scheme's energy and the blow-up message."""

import numpy as np
import pytest
import scipy.sparse as sp

from pdverify.core.errors import SolveError
from pdverify.numerics.explicit import integrate, mass_factor


def test_block_mass_factor_inverts_the_cholesky_blocks():
    M = sp.block_diag([np.array([[4.0, 1.0], [1.0, 3.0]]), np.array([[2.0]]), np.array([[5.0, 2.0], [2.0, 2.0]])])
    Ri = mass_factor(M.tocsr()).toarray()
    assert np.allclose(Ri @ M.toarray() @ Ri.T, np.eye(5), atol=1e-15)


def spring_chain(n, asym=0.0):
    K = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1]).tolil()
    K[0, 1] += asym  # a non-symmetric closure row with a real spectrum
    return K.tocsr()


@pytest.mark.parametrize("asym", [0.0, -0.3])
def test_undamped_run_conserves_the_scheme_energy_to_round_off(asym):
    """A chain of springs under a step load: the scheme's discrete energy (physical, or modal for the non-symmetric
    chain) changes by at most 10 eps per step (round-off of each step's update); stored energy never exceeds the
    work put in by more than that."""
    n = 30
    run = integrate(spring_chain(n, asym), np.ones(n), np.ones(n), 200.0, lambda u: u[:1])
    assert run.ledger == ("physical" if asym == 0 else "modal")
    assert run.scheme_drift < 10 * np.finfo(float).eps * run.steps
    # the default step 0.9 x the limit, shortened to whole steps that end at t_end (by less than one step's share)
    assert run.dt <= 0.9 * run.dt_limit < run.dt * (1 + 1 / (run.steps - 1))
    assert run.dt * run.steps == pytest.approx(200.0, rel=1e-14)


def test_a_step_above_the_limit_blows_up_in_one_line():
    n = 30
    K = spring_chain(n)
    limit = integrate(K, np.ones(n), np.ones(n), 1.0, lambda u: u[:1]).dt_limit
    with pytest.raises(SolveError) as e:
        integrate(K, np.ones(n), np.ones(n), 2000 * limit, lambda u: u[:1], dt=1.05 * limit)
    assert "stable limit" in str(e.value) and "\n" not in str(e.value)


def test_damped_run_settles_on_the_static_solution():
    """Critical damping ratio 1 of the first mode: after t, every mode has decayed by exp(-omega_1 t) at least
    (mass-proportional damping c = 2 omega_1: each mode's envelope decays at c/2); t = 40 / omega_1."""
    n = 10
    K = spring_chain(n)
    b = np.ones(n)
    w1 = np.sqrt(np.linalg.eigvalsh(K.toarray())[0])
    run = integrate(K, np.ones(n), b, 40 / w1, lambda u: u[:1], damping_ratio=1.0)
    static = np.linalg.solve(K.toarray(), b)
    assert np.abs(run.final - static).max() < 50 * np.exp(-40) * np.abs(static).max() + 1e-12
