"""Supports by elimination: fixed DOFs and rigid ties to reference nodes (master-slave).

The nodal DOF vector u (3 per node, interleaved) is written as

    u = T q + u_p,

q the reduced unknowns: the DOFs of nodes that are neither fixed nor tied (in their order), then the
free DOFs of the reference nodes. A node i tied to reference point p (frame R = [e1 e2 e3], e3 the axis)
moves rigidly with it (small rotations):

    u_i = R a + (R theta) x (x_i - p) = [R | -[x_i - p]_x R] (a, theta),

a, theta the reference translations and rotations in the frame R (``ux .. rz``). Reference DOFs
not free are held at 0, or at the prescribed rotation for ``rz``; they enter u_p. The reduced
system is  T^T K T q = T^T (f - K u_p) + f_ref, with f_ref the generalized forces on the
reference DOFs: (R^T F, R^T M + T e3) for force F, moment M and torque T about the axis.
Components of a tied node that a Fixed set holds stay at zero (symmetry planes through a rigid
surface). Ties are exact (no penalty), as ABAQUS rigid bodies in the report.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from fem.mesh.hexmesh import HexMesh
from fem.errors import FEInputError

from fem.model import RIGID_DOFS, FEModel, Fixed, Rigid

__all__ = ["known_names", "set_nodes", "RigidRef", "Reduction", "reduction", "axis_frame"]


def known_names(names) -> str:
    """The first dozen of some names, sorted, for an error message."""
    known = sorted(names)
    return ", ".join(known[:12]) + (" ..." if len(known) > 12 else "")


def set_nodes(mesh: HexMesh, name: str, field: str) -> np.ndarray:
    """Node indices of a point set or face set called ``name`` (FEInputError naming `field` if absent)."""
    if name in mesh.point_sets:
        return mesh.point_sets[name]
    if name in mesh.face_sets:
        return mesh.face_set_points(name)
    raise FEInputError(field, name, f"a point or face set of the mesh ({known_names(set(mesh.point_sets) | set(mesh.face_sets))})")


def axis_frame(axis) -> np.ndarray:
    """Orthonormal frame (3, 3), columns e1, e2 = e3 x e1, e3 = axis / |axis| (global for axis z)."""
    e3 = np.asarray(axis, float)
    n = np.linalg.norm(e3)
    if not n > 0:
        raise FEInputError("reference axis", tuple(axis), "a nonzero vector")
    e3 = e3 / n
    # e1: the global x axis made normal to the axis (y if the axis is near x), so that the frame
    # of an axis along z is the global one
    helper = np.eye(3)[0] if abs(e3[0]) < 0.9 else np.eye(3)[1]
    e1 = helper - (helper @ e3) * e3
    e1 /= np.linalg.norm(e1)
    return np.stack([e1, np.cross(e3, e1), e3], axis=1)


@dataclass(frozen=True, eq=False)
class RigidRef:
    """A reference node: body, point [mm], frame, reduced column of each of its 6 DOFs (-1: held)."""

    body: str
    reference: str
    point: np.ndarray
    frame: np.ndarray
    columns: np.ndarray
    prescribed: np.ndarray
    nodes: np.ndarray


@dataclass(frozen=True, eq=False)
class Reduction:
    """u = T q + u_p; loads on reference DOFs; which reduced DOFs are free rigid DOFs."""

    T: sp.csr_matrix
    u_prescribed: np.ndarray
    f_ref: np.ndarray
    free_rigid: np.ndarray
    fixed: np.ndarray  # (3n,) bool
    free_dof: np.ndarray  # (3n,) bool: neither fixed nor tied; reduced DOF i is the i-th of them (i < n - len(free_rigid))
    support_nodes: dict  # body -> nodes held by a Fixed set or tied to a reference
    rigid: tuple[RigidRef, ...]

    @property
    def n(self) -> int:
        return self.T.shape[1]

    def expand(self, q: np.ndarray) -> np.ndarray:
        """Nodal displacements (n, 3) [mm] from reduced unknowns."""
        return (self.T @ q + self.u_prescribed).reshape(-1, 3)

    def rigid_motion(self, q: np.ndarray) -> dict:
        """Per rigid body: translation [mm] and rotation [rad] of its reference node (global)."""
        out = {}
        for r in self.rigid:
            v = np.where(r.columns >= 0, q[np.maximum(r.columns, 0)], r.prescribed)
            out[r.body] = (r.frame @ v[:3], r.frame @ v[3:])
        return out


def _cross_matrix(r: np.ndarray) -> np.ndarray:
    z = np.zeros(len(r))
    return np.stack([np.stack([z, -r[:, 2], r[:, 1]], -1), np.stack([r[:, 2], z, -r[:, 0]], -1),
                     np.stack([-r[:, 1], r[:, 0], z], -1)], axis=1)


def reduction(mesh: HexMesh, model: FEModel) -> Reduction:
    """Build T, u_p and reference loads from the bodies' supports."""
    n = mesh.n_points
    fixed = np.zeros(3 * n, bool)
    tied = np.full(n, -1)  # index of the Rigid tie holding the node
    ties: list[tuple[str, Rigid, np.ndarray]] = []
    support_nodes = {}
    names = set(mesh.bodies)
    for b in model.bodies:
        if b.name not in names:
            raise FEInputError("bodies.name", b.name, "a body of the mesh (" + ", ".join(mesh.bodies) + ")")
        if not b.supports:
            raise FEInputError(f"bodies[{b.name!r}].supports", (), "at least one Fixed or Rigid support (an unsupported body is singular)")
        body_nodes = np.unique(mesh.cells[mesh.body_cells(b.name)])
        held = []
        for i, s in enumerate(b.supports):
            field = f"bodies[{b.name!r}].supports[{i}].set"
            nodes = set_nodes(mesh, s.set, field)
            if not np.isin(nodes, body_nodes).all():
                raise FEInputError(field, s.set, f"a set of nodes of body {b.name!r}")
            held.append(nodes)
            if isinstance(s, Fixed):
                for c in s.components:
                    fixed[3 * nodes + c] = True
            else:
                if s.reference not in mesh.reference_points:
                    raise FEInputError(f"bodies[{b.name!r}].supports[{i}].reference", s.reference,
                                     "a reference point of the mesh (" + ", ".join(mesh.reference_points) + ")")
                ties.append((b.name, s, nodes))
        support_nodes[b.name] = np.unique(np.concatenate(held))
    missing = names - {b.name for b in model.bodies}
    if missing:
        raise FEInputError("bodies", sorted(missing), "an entry with supports for every body of the mesh")
    for k, (body, s, nodes) in enumerate(ties):
        nodes = nodes[~fixed.reshape(-1, 3)[nodes].all(axis=1)]
        if np.any(tied[nodes] >= 0):
            raise FEInputError(f"bodies[{body!r}]", s.set, "a node tied to one reference node only")
        tied[nodes] = k
    free_dof = ~fixed & np.repeat(tied < 0, 3)
    n_free = int(free_dof.sum())
    col = -np.ones(3 * n, np.int64)
    col[free_dof] = np.arange(n_free)
    rows = [np.flatnonzero(free_dof)]
    cols = [col[free_dof]]
    vals = [np.ones(n_free)]
    u_p = np.zeros(3 * n)
    next_col = n_free
    refs, f_ref_parts = [], []
    for k, (body, s, _) in enumerate(ties):
        rp = mesh.reference_points[s.reference]
        p = np.asarray(rp.point, float)
        R = axis_frame(rp.axis)
        columns = -np.ones(6, np.int64)
        prescribed = np.zeros(6)
        for j, name in enumerate(RIGID_DOFS):
            if name in s.free:
                columns[j] = next_col
                next_col += 1
        prescribed[5] = s.rotation
        nodes = np.flatnonzero(tied == k)
        Tn = np.concatenate([np.broadcast_to(R, (len(nodes), 3, 3)), -_cross_matrix(mesh.points[nodes] - p) @ R], axis=2)  # (k, 3, 6)
        d = (3 * nodes[:, None] + np.arange(3)).ravel()
        moving = ~fixed[d]  # components held by a Fixed set stay at zero
        for j in range(6):
            if columns[j] >= 0:
                rows.append(d[moving])
                cols.append(np.full(int(moving.sum()), columns[j]))
                vals.append(Tn[:, :, j].ravel()[moving])
            elif prescribed[j] != 0.0:
                u_p[d[moving]] += Tn[:, :, j].ravel()[moving] * prescribed[j]
        gen = np.concatenate([R.T @ np.asarray(s.force), R.T @ np.asarray(s.moment) + np.array([0.0, 0.0, s.torque])])
        f_ref_parts.append((columns, gen))
        refs.append(RigidRef(body, s.reference, p, R, columns, prescribed, nodes))
    T = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(3 * n, next_col))
    f_ref = np.zeros(next_col)
    for columns, gen in f_ref_parts:
        f_ref[columns[columns >= 0]] += gen[columns >= 0]
    free_rigid = np.arange(n_free, next_col)
    return Reduction(T, u_p, f_ref, free_rigid, fixed, free_dof, support_nodes, tuple(refs))
