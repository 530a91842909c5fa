"""Linear elasticity, penalty contact, rigid bodies and loads, stress recovery.

``solve(mesh, model) -> FEResult`` on a :class:`fem.mesh.HexMesh`; the model names bodies with
their supports (``Fixed``, ``Rigid``) and loads (``Traction``, torques), materials, contact
pairs and options. See ``fem.solve`` for the steps and each module for its maths.
"""

from fem.material import STEEL, Material
from fem.model import Body, ContactOptions, ContactPair, FEModel, Fixed, Rigid, SolverOptions, Traction
from fem.result import FEResult, PairResult, SolveInfo, torque_balance_error
from fem.analysis import solve

__all__ = [
    "Material",
    "STEEL",
    "Fixed",
    "Rigid",
    "Traction",
    "Body",
    "ContactPair",
    "ContactOptions",
    "SolverOptions",
    "FEModel",
    "FEResult",
    "PairResult",
    "SolveInfo",
    "solve",
    "torque_balance_error",
]
