"""Results of a solve: nodal fields, contact per pair and member, reactions, timings, VTU output.

Contact pressure is nodal (slave nodes) [MPa]: with the default Gauss-point constraints the
projection of the nodal normal forces described in ``fem.contact`` ("Pressure"); with node
constraints the node's force divided by its tributary area. ``contact_force`` holds the nodal
normal forces [N]. The contact area of a pair [mm^2] is the area of its closed Gauss points (gap
below the solution's largest penetration; node constraints: the tributary areas of the active
nodes); its force is the sum of the normal forces lambda [N]; ``semi_axes`` are the Hertz-equivalent
semi-axes of its nodal forces (``fem.contact.contact_patch``). Load share is each pair's (tooth's)
and each group's (member's) fraction of the total normal contact force.

Support reactions are the nodal forces the supports exert, r = K u - f - G^T lambda, at nodes
held by a Fixed set or tied to a reference node; ``support_torque`` is their moment about an
axis. For a fixed sun this is the reaction torque compared with the applied torque times the
gear ratio (``torque_balance_error``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from fem.mesh.hexmesh import HexMesh
from fem.errors import FEInputError

from fem.constraints import set_nodes
from fem.model import FEModel

__all__ = ["PairResult", "SolveInfo", "FEResult", "torque_balance_error", "STRESS_RECOVERY"]

STRESS_RECOVERY = "2x2x2 Gauss-point stresses (incompatible modes included) extrapolated to the corner nodes, averaged over the cells of each node"


@dataclass(frozen=True)
class PairResult:
    """One contact pair (tooth): normal force [N], force vector on the slave [N], area [mm^2], peak [MPa],
    numbers of active and candidate slave nodes."""

    name: str
    group: str
    force: float
    force_vector: tuple[float, float, float]
    area: float
    max_pressure: float
    active_nodes: int
    candidates: int
    semi_axes: tuple[float, float] = (0.0, 0.0)  # Hertz-equivalent a >= b of the nodal forces [mm] (fem.contact.contact_patch)


@dataclass(frozen=True)
class SolveInfo:
    """Sizes, solver, active-set and penalty statistics, and timings [s]."""

    dofs: int
    reduced_dofs: int
    schur_dofs: int
    solver: str
    element: str
    candidates: int = 0
    active: int = 0
    iterations: int = 0
    penalty_scale: float = 1.0
    penalty_change: float = float("nan")
    max_penetration: float = 0.0
    timings: dict = field(default_factory=dict)


@dataclass(frozen=True, eq=False)
class FEResult:
    """Displacements [mm], nodal stresses [MPa], contact and reactions of one solve."""

    mesh: HexMesh
    model: FEModel
    displacement: np.ndarray  # (n, 3)
    stress: np.ndarray  # (n, 6) xx yy zz xy yz xz
    von_mises: np.ndarray  # (n,)
    principal: np.ndarray  # (n, 3) descending
    contact_pressure: np.ndarray  # (n,)
    contact_gap: np.ndarray  # (n,) deformed gap at slave nodes [mm], nan elsewhere
    pairs: tuple[PairResult, ...]
    reaction: np.ndarray  # (n, 3) support forces [N]
    rigid_motion: dict  # body -> (translation [mm], rotation [rad])
    info: SolveInfo
    contact_force: np.ndarray | None = None  # (n,) normal contact force per slave node [N] (0 elsewhere)

    def load_share(self) -> dict:
        """Fractions of the total normal contact force per pair (tooth) and per group (member)."""
        total = sum(p.force for p in self.pairs)
        if total <= 0.0:
            return {"pairs": {p.name: 0.0 for p in self.pairs}, "groups": {}}
        groups: dict[str, float] = {}
        for p in self.pairs:
            groups[p.group] = groups.get(p.group, 0.0) + p.force / total
        return {"pairs": {p.name: p.force / total for p in self.pairs}, "groups": groups}

    def max_on_set(self, name: str, values: str = "von_mises") -> float:
        """Largest nodal value of a field ('von_mises', 'max_principal') on a point or face set."""
        nodes = set_nodes(self.mesh, name, "set")
        v = {"von_mises": self.von_mises, "max_principal": self.principal[:, 0]}.get(values)
        if v is None:
            raise FEInputError("values", values, "'von_mises' or 'max_principal'")
        return float(v[nodes].max())

    def fillet_stress(self) -> dict:
        """Per fillet set of the model: max von Mises and max principal stress [MPa]."""
        return {s: {"max_von_mises_mpa": self.max_on_set(s), "max_principal_mpa": self.max_on_set(s, "max_principal")}
                for s in self.model.fillet_sets}

    def support_torque(self, body: str, point=None, axis=None) -> float:
        """Moment [N mm] of the support reactions of a body about an axis (default: its reference point)."""
        if point is None:
            if body not in self.mesh.reference_points:
                raise FEInputError("point", None, f"an axis point, or a reference point named {body!r} in the mesh")
            rp = self.mesh.reference_points[body]
            point, axis = rp.point, rp.axis if axis is None else axis
        axis = np.asarray((0.0, 0.0, 1.0) if axis is None else axis, float)
        axis = axis / np.linalg.norm(axis)
        nodes = np.unique(self.mesh.cells[self.mesh.body_cells(body)])
        m = np.cross(self.mesh.points[nodes] - np.asarray(point, float), self.reaction[nodes]).sum(axis=0)
        return float(m @ axis)

    def summary(self, torque_balance: float | None = None) -> dict:
        """The numbers of ``summary.json`` (``gearfe stress``)."""
        pairs = self.pairs
        out = {
            "max_von_mises_mpa": float(self.von_mises.max()),
            "max_contact_pressure_mpa": float(self.contact_pressure.max(initial=0.0)),
            "contact_force_n": float(sum(p.force for p in pairs)),
            "contact_area_mm2": float(sum(p.area for p in pairs)),
            "torque_balance_error": None if torque_balance is None else float(torque_balance),
            "dofs": int(self.info.dofs),
            "solve_s": float(self.info.timings.get("total_s", float("nan"))),
            "load_share": self.load_share(),
            "pairs": {p.name: {"group": p.group, "force_n": p.force, "area_mm2": p.area, "max_pressure_mpa": p.max_pressure,
                               "active_nodes": p.active_nodes, "semi_axes_mm": list(p.semi_axes)} for p in pairs},
            "fillet": self.fillet_stress(),
            "solver": self.info.solver,
            "element": self.info.element,
            "stress_recovery": STRESS_RECOVERY,
            "active_set_iterations": self.info.iterations,
            "penalty_scale": self.info.penalty_scale,
            "penalty_doubling_change": self.info.penalty_change,
            "max_penetration_mm": self.info.max_penetration,
            "timings_s": dict(self.info.timings),
        }
        return out

    def write_vtu(self, path) -> None:
        """Write the mesh with all nodal fields and the body id per cell (meshio, VTU)."""
        import meshio

        point_data = {
            "displacement": self.displacement,
            "stress": self.stress,
            "von_mises": self.von_mises,
            "principal_stress": self.principal,
            "max_principal": self.principal[:, 0],
            "min_principal": self.principal[:, 2],
            "contact_pressure": self.contact_pressure,
            "contact_force": np.zeros(len(self.contact_pressure)) if self.contact_force is None else self.contact_force,
            "contact_gap": np.nan_to_num(self.contact_gap, nan=-1.0),
            "reaction": self.reaction,
        }
        cell_data = {"body": [self.mesh.cell_body.astype(np.int32)]}
        meshio.Mesh(self.mesh.points, [("hexahedron", self.mesh.cells)], point_data=point_data, cell_data=cell_data).write(
            str(path), file_format="vtu"
        )


def torque_balance_error(result: FEResult, body: str, expected_torque: float, point=None, axis=None) -> float:
    """|T_support(body) - expected| / |expected|: reaction torque vs applied torque x ratio."""
    if expected_torque == 0.0:
        raise FEInputError("expected_torque", expected_torque, "a nonzero torque [N mm]")
    return abs(result.support_torque(body, point, axis) - expected_torque) / abs(expected_torque)
