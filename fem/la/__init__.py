"""Linear algebra of the engine: sparse solves with a Schur complement, PARDISO, condensed compliances.
"""

from fem.la.linsolve import SchurSystem, choose_solver, linear_solve, schur_system
from fem.la.condense import influence_matrix

__all__ = ["SchurSystem", "choose_solver", "linear_solve", "schur_system", "influence_matrix"]
