"""Batched Newton (tca.numerics.newton): failures are reported, not returned silently."""

import numpy as np
import pytest

from tca.errors import ConvergenceError
from tca.numerics.newton import newton


def test_newton_failure_names_the_position():
    def fun(x, idx):  # x^2 + 1 = 0 has no real root
        return x**2 + 1.0, 2 * x[:, :, None]

    with pytest.raises(ConvergenceError, match="phi1 = 7.5 deg"):
        newton(fun, np.array([[0.3]]), where=lambda i: "phi1 = 7.5 deg")


def test_newton_isolates_a_member_that_leaves_the_domain():
    # sqrt(x) - 2 = 0: a member started at x < 0 has a non-finite residual and fails on its own
    def fun(x, idx):
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.sqrt(x) - 2.0, (0.5 / np.sqrt(x))[:, :, None]

    r = newton(fun, np.array([[1.0], [-1.0], [9.0]]), raise_on_failure=False)
    assert list(r.converged) == [True, False, True]
    assert np.allclose(r.x[[0, 2], 0], 4.0)
