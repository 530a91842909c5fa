"""Errors raised by the FE engine: each names the field, the value and what would be valid.

The engine knows nothing of gears; an application (``pipelines``) reports these to its user in one
line, as it does its own errors.
"""

from __future__ import annotations

__all__ = ["FEError", "FEInputError", "FEConvergenceError"]


class FEError(Exception):
    """Base class of all errors of the FE engine that its user can act on."""


class FEInputError(FEError, ValueError):
    """A model, mesh or option is out of its valid range (names key, value and range)."""

    def __init__(self, field: str, value, valid: str, why: str = ""):
        self.field, self.value, self.valid, self.why = field, value, valid, why
        msg = f"{field} = {value!r} is invalid: expected {valid}"
        if why:
            msg += f" ({why})"
        super().__init__(msg)


class FEConvergenceError(FEError, RuntimeError):
    """An iterative solve (contact active set, Krylov solver) did not converge; names where and how far off."""

    def __init__(self, what: str, where: str, residual: float, iterations: int):
        self.what, self.where, self.residual, self.iterations = what, where, residual, iterations
        super().__init__(
            f"{what} did not converge at {where}: residual {residual:.3e} after {iterations} iterations"
        )
