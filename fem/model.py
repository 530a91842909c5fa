"""The finite-element model: bodies, their supports and loads, contact pairs and solver options.

A model refers to a :class:`fem.mesh.HexMesh` only by names: bodies by ``mesh.bodies``, sets by
``"<body>/<set>"`` keys of ``mesh.point_sets`` or ``mesh.face_sets`` (a face set stands for its
nodes where nodes are needed), reference nodes by keys of ``mesh.reference_points``.

Boundary conditions of the report (section 1.6, Fig. 1.7) in these terms:

    sun     Fixed("sun/rim")                                       rim sides and bottom fixed
    planet  Rigid("planet/rim", "planet", free=("rz",))           rotation about its axis free
    ring    Rigid("ring/rim", "ring", free=("rz",), torque=5e5)   T = 500 N m = 5e5 N mm

Rigid-body degrees of freedom are named in the frame of the reference point, whose z axis is
the reference axis: ``ux, uy, uz`` translations [mm], ``rx, ry, rz`` rotations [rad]. Those
not listed in ``free`` are held at zero, except ``rz`` which may be prescribed (``rotation``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from fem.errors import FEInputError

from fem.material import STEEL, Material

__all__ = [
    "RIGID_DOFS",
    "Fixed",
    "Rigid",
    "Traction",
    "Body",
    "ContactPair",
    "ContactOptions",
    "SolverOptions",
    "FEModel",
]

RIGID_DOFS = ("ux", "uy", "uz", "rx", "ry", "rz")
SOLVERS = ("auto", "pardiso", "superlu")
ELEMENTS = ("hex8i", "hex8")


def _vec3(name: str, v) -> tuple[float, float, float]:
    try:
        t = tuple(float(x) for x in v)
    except TypeError:
        raise FEInputError(name, v, "a sequence of 3 numbers") from None
    if len(t) != 3 or not all(math.isfinite(x) for x in t):
        raise FEInputError(name, v, "3 finite numbers")
    return t


@dataclass(frozen=True)
class Fixed:
    """Nodes of a node or face set held at zero displacement in the given global components."""

    set: str
    components: tuple[int, ...] = (0, 1, 2)

    def __post_init__(self):
        comps = tuple(int(c) for c in self.components)
        if not comps or any(c not in (0, 1, 2) for c in comps) or len(set(comps)) != len(comps):
            raise FEInputError(f"Fixed({self.set!r}).components", self.components, "distinct values from 0, 1, 2 (x, y, z)")
        object.__setattr__(self, "components", comps)


@dataclass(frozen=True)
class Rigid:
    """Nodes of a set tied rigidly to a reference node, its free DOFs loaded by force/moment/torque.

    ``torque`` [N mm] acts about the reference axis; ``force`` [N] and ``moment`` [N mm] are
    global vectors at the reference point; ``rotation`` [rad] prescribes ``rz`` when it is not free.
    """

    set: str
    reference: str
    free: tuple[str, ...] = ("rz",)
    torque: float = 0.0
    force: tuple[float, float, float] = (0.0, 0.0, 0.0)
    moment: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rotation: float = 0.0

    def __post_init__(self):
        free = tuple(self.free)
        bad = [d for d in free if d not in RIGID_DOFS]
        if bad or len(set(free)) != len(free):
            raise FEInputError(f"Rigid({self.set!r}).free", self.free, f"distinct names from {RIGID_DOFS}")
        object.__setattr__(self, "free", free)
        for name in ("torque", "rotation"):
            v = getattr(self, name)
            if not math.isfinite(float(v)):
                raise FEInputError(f"Rigid({self.set!r}).{name}", v, "a finite number")
            object.__setattr__(self, name, float(v))
        object.__setattr__(self, "force", _vec3(f"Rigid({self.set!r}).force", self.force))
        object.__setattr__(self, "moment", _vec3(f"Rigid({self.set!r}).moment", self.moment))
        if self.torque != 0.0 and "rz" not in free:
            raise FEInputError(f"Rigid({self.set!r}).torque", self.torque, "0 unless 'rz' is in free (a torque on a held rotation does no work)")
        if self.rotation != 0.0 and "rz" in free:
            raise FEInputError(f"Rigid({self.set!r}).rotation", self.rotation, "0 when 'rz' is free (a DOF is either free or prescribed)")


@dataclass(frozen=True)
class Traction:
    """Uniform surface traction [MPa] (global vector) on a face set."""

    set: str
    traction: tuple[float, float, float]

    def __post_init__(self):
        object.__setattr__(self, "traction", _vec3(f"Traction({self.set!r}).traction", self.traction))


@dataclass(frozen=True)
class Body:
    """A body of the mesh: its material, supports (Fixed/Rigid) and surface loads."""

    name: str
    supports: tuple = ()
    material: Material = STEEL
    loads: tuple[Traction, ...] = ()

    def __post_init__(self):
        object.__setattr__(self, "supports", tuple(self.supports))
        object.__setattr__(self, "loads", tuple(self.loads))
        for s in self.supports:
            if not isinstance(s, (Fixed, Rigid)):
                raise FEInputError(f"bodies[{self.name!r}].supports", s, "Fixed or Rigid entries")
        for s in self.loads:
            if not isinstance(s, Traction):
                raise FEInputError(f"bodies[{self.name!r}].loads", s, "Traction entries")
        if len([s for s in self.supports if isinstance(s, Rigid)]) > 1:
            raise FEInputError(f"bodies[{self.name!r}].supports", self.supports, "at most one Rigid support per body")


@dataclass(frozen=True)
class ContactPair:
    """Node-to-surface contact: nodes of the ``slave`` face set against faces of ``master``.

    ``search_gap`` [mm]: slave nodes with an initial normal gap below it are contact candidates
    (the solver checks afterwards that no other node penetrates). ``contact_point`` [mm] and
    ``contact_radius`` [mm] (e.g. from TCA) seed the initial active set; ``group`` names the
    member for load sharing (defaults to the slave body).
    """

    slave: str
    master: str
    name: str = ""
    group: str = ""
    search_gap: float = 0.1
    contact_point: tuple[float, float, float] | None = None
    contact_radius: float = 0.0

    def __post_init__(self):
        if not self.name:
            object.__setattr__(self, "name", self.slave)
        if not self.group:
            object.__setattr__(self, "group", self.slave.split("/")[0])
        if not (self.search_gap > 0.0 and math.isfinite(self.search_gap)):
            raise FEInputError(f"contacts[{self.name!r}].search_gap", self.search_gap, "a gap > 0 mm")
        if not (self.contact_radius >= 0.0):
            raise FEInputError(f"contacts[{self.name!r}].contact_radius", self.contact_radius, "a radius >= 0 mm")
        if self.contact_point is not None:
            object.__setattr__(self, "contact_point", _vec3(f"contacts[{self.name!r}].contact_point", self.contact_point))


@dataclass(frozen=True)
class ContactOptions:
    """Penalty and active-set settings.

    ``quadrature`` = 0: one constraint per slave node, its own gap (node-to-surface); n = 2, 3, 4:
    n x n Gauss points per slave face, each a constraint (``points = 'gauss'``, default: the
    contact edge resolved to a Gauss point, issue 14) or their gaps averaged per slave node
    (``points = 'nodes'``, issue 6). The penalty per unit area is
    ``penalty_factor * E / h`` [MPa/mm], h the thickness of the slave element under the point. ``max_penetration`` [mm] bounds the penalty penetration;
    ``penalty_check`` re-solves with the penalty doubled and requires the peak pressure to change
    by less than ``penalty_check_tol`` (relative).
    """

    penalty_factor: float = 100.0
    max_penetration: float = 1e-4
    max_iterations: int = 60
    penalty_check: bool = True
    penalty_check_tol: float = 0.01
    quadrature: int = 2
    points: str = "gauss"

    def __post_init__(self):
        if self.points not in ("nodes", "gauss"):
            raise FEInputError("contact.points", self.points, "'nodes' (averaged gap per slave node) or 'gauss' (one per Gauss point)")
        if self.quadrature not in (0, 2, 3, 4):
            raise FEInputError("contact.quadrature", self.quadrature, "0 (slave nodes) or 2, 3, 4 (n x n Gauss points per slave face)",
                             "one point per face leaves the averaged gaps of neighbouring nodes dependent")
        if not (self.penalty_factor > 0.0 and math.isfinite(self.penalty_factor)):
            raise FEInputError("contact.penalty_factor", self.penalty_factor, "a factor > 0 (penalty = factor * E / h)")
        if not (self.max_penetration > 0.0):
            raise FEInputError("contact.max_penetration", self.max_penetration, "a penetration > 0 mm")
        if not (isinstance(self.max_iterations, int) and self.max_iterations >= 1):
            raise FEInputError("contact.max_iterations", self.max_iterations, "an integer >= 1")
        if not (0.0 < self.penalty_check_tol < 1.0):
            raise FEInputError("contact.penalty_check_tol", self.penalty_check_tol, "a fraction in (0, 1)")


@dataclass(frozen=True)
class SolverOptions:
    """Linear solver ('auto' = PARDISO when MKL loads, else SuperLU) and element ('hex8i', 'hex8')."""

    solver: str = "auto"
    element: str = "hex8i"

    def __post_init__(self):
        if self.solver not in SOLVERS:
            raise FEInputError("solver.solver", self.solver, "one of " + ", ".join(SOLVERS))
        if self.element not in ELEMENTS:
            raise FEInputError("solver.element", self.element, "one of " + ", ".join(ELEMENTS))


@dataclass(frozen=True)
class FEModel:
    """Bodies, contact pairs, options, and the sets whose peak (fillet) stress is reported."""

    bodies: tuple[Body, ...]
    contacts: tuple[ContactPair, ...] = ()
    contact: ContactOptions = field(default_factory=ContactOptions)
    solver: SolverOptions = field(default_factory=SolverOptions)
    fillet_sets: tuple[str, ...] = ()

    def __post_init__(self):
        object.__setattr__(self, "bodies", tuple(self.bodies))
        object.__setattr__(self, "contacts", tuple(self.contacts))
        object.__setattr__(self, "fillet_sets", tuple(self.fillet_sets))
        names = [b.name for b in self.bodies]
        if not names:
            raise FEInputError("bodies", (), "at least one body")
        if len(set(names)) != len(names):
            raise FEInputError("bodies", names, "distinct body names")
        pairs = [c.name for c in self.contacts]
        if len(set(pairs)) != len(pairs):
            raise FEInputError("contacts", pairs, "distinct contact pair names")

    def body(self, name: str) -> Body:
        """The body called ``name``."""
        for b in self.bodies:
            if b.name == name:
                return b
        raise FEInputError("body", name, "one of " + ", ".join(b.name for b in self.bodies))
