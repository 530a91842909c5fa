"""The errors a user can act on, from every layer: gear geometry and TCA (:mod:`tca.errors`) and the FE
engine (:mod:`fem.errors`). The command line turns any of them into one line and exit status 2."""

from __future__ import annotations

from fem.errors import FEConvergenceError, FEError, FEInputError
from tca.errors import ConvergenceError, GearfeError, InputError

__all__ = ["USER_ERRORS", "INPUT_ERRORS", "CONVERGENCE_ERRORS"]

USER_ERRORS = (GearfeError, FEError)
INPUT_ERRORS = (InputError, FEInputError)
CONVERGENCE_ERRORS = (ConvergenceError, FEConvergenceError)
