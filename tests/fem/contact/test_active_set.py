"""The reduced contact problem on its own: a rigid block on two penalty springs, against the closed form.

One free rigid DOF u [mm] closes two gaps g_i = g0_i - u (B = [1, 1]^T, rigid bodies: W = 0, no
stiffness before contact: H = 0) under a force F [N]; the penalty law lambda_i = k <u - g0_i>
and the balance lambda_1 + lambda_2 = F give, with g0 = (0, d):

    F <= k d:  u = F / k,               lambda = (F, 0);
    F >  k d:  u = (F + k d) / (2 k),   lambda = (k u, k (u - d)).
"""

import numpy as np
import pytest

from fem import ContactOptions
from fem.contact.active_set import ReducedContact, active_set, penalty_active_set
from fem.errors import FEError

K = 1.0e6  # [N/mm]
D = 1.0e-3  # [mm]


def two_springs(force: float) -> ReducedContact:
    return ReducedContact(W=np.zeros((2, 2)), B=np.ones((2, 1)), H=np.zeros((1, 1)), ghat=np.array([0.0, D]),
                          fhat=np.array([force]), h_scale=np.array([K]))


@pytest.mark.parametrize("force", [0.5 * K * D, 3.0 * K * D])
def test_two_springs_closed_form(force):
    sol = active_set(two_springs(force), np.full(2, K), np.array([True, False]), max_iterations=10)
    u = force / K if force <= K * D else (force + K * D) / (2 * K)
    lam = np.array([K * u, max(K * (u - D), 0.0)])
    # round-off of a 2 x 2 Cholesky solve
    assert sol.u_free[0] == pytest.approx(u, rel=1e-12)
    np.testing.assert_allclose(sol.lam, lam, rtol=1e-12, atol=1e-9 * force)
    assert sol.lam.sum() == pytest.approx(force, rel=1e-12)
    np.testing.assert_array_equal(sol.active, lam > 0)


def test_penalty_is_raised_until_the_penetration_is_within_the_tolerance():
    force = 0.5 * K * D  # penetration F / k = D / 2 = 5e-4 mm at the starting penalty
    opts = ContactOptions(max_penetration=1e-5, penalty_check=False)
    sol = penalty_active_set(two_springs(force), np.full(2, K), np.ones(2), np.array([True, False]), opts)
    assert sol.scale > 1.0
    assert -sol.gap[sol.active].min() <= opts.max_penetration
    assert sol.lam.sum() == pytest.approx(force, rel=1e-12)


def test_a_free_dof_no_contact_holds_is_refused():
    open_gaps = ReducedContact(W=np.zeros((2, 2)), B=np.ones((2, 1)), H=np.zeros((1, 1)), ghat=np.array([0.1, 0.2]),
                               fhat=np.array([-1.0]), h_scale=np.array([K]))
    with pytest.raises(FEError, match="not held by any active contact"):
        active_set(open_gaps, np.full(2, K), np.zeros(2, bool), max_iterations=10)
