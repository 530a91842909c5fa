"""Errors raised by gearfe: each names the field, the value and what would be valid.

Every package (``tca``, ``mesher``, ``fem``, ``pipelines``) raises these, so the command line
can turn any of them into a one-line message and exit status 2.
"""

from __future__ import annotations

__all__ = [
    "GearfeError",
    "InputError",
    "GeometryError",
    "ConvergenceError",
]


class GearfeError(Exception):
    """Base class of all errors that gearfe reports to its user."""


class InputError(GearfeError, ValueError):
    """A value given by the user is out of its valid range (names key, value and range)."""

    def __init__(self, field: str, value, valid: str, why: str = ""):
        self.field, self.value, self.valid, self.why = field, value, valid, why
        msg = f"{field} = {value!r} is invalid: expected {valid}"
        if why:
            msg += f" ({why})"
        super().__init__(msg)


class GeometryError(GearfeError, ValueError):
    """A gear or gear pair cannot be made as asked (undercut, pointed tooth, interference...)."""

    def __init__(self, gear: str, cause: str, detail: str):
        self.gear, self.cause = gear, cause
        super().__init__(f"{gear}: {cause}: {detail}")


class ConvergenceError(GearfeError, RuntimeError):
    """A Newton solve did not converge; names where (position) and how far off it stayed."""

    def __init__(self, what: str, where: str, residual: float, iterations: int):
        self.what, self.where, self.residual, self.iterations = what, where, residual, iterations
        super().__init__(
            f"{what} did not converge at {where}: residual {residual:.3e} after {iterations} iterations"
        )
