"""Hexahedral mesh container shared by the mesher and the FE solver.

Node order of a hexahedron is VTK_HEXAHEDRON's (= ABAQUS C3D8's): nodes 0-3 one quadrilateral,
4-7 the opposite one, node i+4 facing node i, and 0-1-2-3 counter-clockwise seen from 4-7, so
that the Jacobian is positive. Local faces, listed with outward normals (right-hand rule):

    face 0 = (0, 3, 2, 1)   ABAQUS S1
    face 1 = (4, 5, 6, 7)   ABAQUS S2
    face 2 = (0, 1, 5, 4)   ABAQUS S3
    face 3 = (1, 2, 6, 5)   ABAQUS S4
    face 4 = (2, 3, 7, 6)   ABAQUS S5
    face 5 = (3, 0, 4, 7)   ABAQUS S6

Face sets are arrays of (cell index, local face) pairs; node sets are sorted unique node indices.
Names are ``"<body>/<set>"``, e.g. ``"planet/flank_drive"`` or ``"sun/rim"``.
``contact_pairs`` lists (face set of body 1, face set of body 2) pairs that may come into contact,
and ``meta`` carries JSON-ready facts about the model (see :mod:`mesher`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Mapping

import numpy as np

from fem.errors import FEInputError

__all__ = ["HEX_FACES", "HexMesh", "ReferencePoint", "merge_meshes"]

HEX_FACES = np.array(
    [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]],
    dtype=np.int64,
)


@dataclass(frozen=True)
class ReferencePoint:
    """A reference node of a rigid body: position [mm] and unit axis of rotation."""

    point: tuple[float, float, float]
    axis: tuple[float, float, float] = (0.0, 0.0, 1.0)


def _frozen(d: Mapping | None) -> Mapping:
    return MappingProxyType(dict(d or {}))


@dataclass(frozen=True, eq=False)
class HexMesh:
    """8-node hexahedral mesh of one or more bodies, with named node, face and reference sets."""

    points: np.ndarray  # (n, 3) float64 [mm]
    cells: np.ndarray  # (m, 8) int64, VTK_HEXAHEDRON order
    cell_body: np.ndarray  # (m,) int64 index into `bodies`
    bodies: tuple[str, ...] = ("body",)
    point_sets: Mapping[str, np.ndarray] = field(default_factory=dict)
    face_sets: Mapping[str, np.ndarray] = field(default_factory=dict)
    reference_points: Mapping[str, ReferencePoint] = field(default_factory=dict)
    contact_pairs: tuple[tuple[str, str], ...] = ()
    meta: Mapping[str, object] = field(default_factory=dict)

    def __post_init__(self):
        pts = np.ascontiguousarray(self.points, dtype=np.float64)
        cells = np.ascontiguousarray(self.cells, dtype=np.int64)
        body = np.ascontiguousarray(self.cell_body, dtype=np.int64)
        if pts.ndim != 2 or pts.shape[1] != 3:
            raise FEInputError("points", pts.shape, "an (n, 3) array")
        if cells.ndim != 2 or cells.shape[1] != 8:
            raise FEInputError("cells", cells.shape, "an (m, 8) array of node indices")
        if cells.size and (cells.min() < 0 or cells.max() >= len(pts)):
            raise FEInputError("cells", (int(cells.min()), int(cells.max())), f"indices in [0, {len(pts) - 1}]")
        if body.shape != (len(cells),):
            raise FEInputError("cell_body", body.shape, f"shape ({len(cells)},)")
        if body.size and (body.min() < 0 or body.max() >= len(self.bodies)):
            raise FEInputError("cell_body", int(body.max()), f"indices into bodies {self.bodies}")
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "cells", cells)
        object.__setattr__(self, "cell_body", body)
        object.__setattr__(self, "bodies", tuple(self.bodies))
        object.__setattr__(
            self, "point_sets", _frozen({k: np.unique(np.asarray(v, np.int64)) for k, v in (self.point_sets or {}).items()})
        )
        object.__setattr__(
            self, "face_sets", _frozen({k: np.asarray(v, np.int64).reshape(-1, 2) for k, v in (self.face_sets or {}).items()})
        )
        object.__setattr__(self, "reference_points", _frozen(self.reference_points))
        object.__setattr__(self, "contact_pairs", tuple((str(a), str(b)) for a, b in self.contact_pairs))
        object.__setattr__(self, "meta", _frozen(self.meta))
        for a, b in self.contact_pairs:
            for n in (a, b):
                if n not in self.face_sets:
                    raise FEInputError("contact_pairs", n, "names of face sets of the mesh")

    @property
    def n_points(self) -> int:
        return len(self.points)

    @property
    def n_cells(self) -> int:
        return len(self.cells)

    def face_nodes(self, name: str) -> np.ndarray:
        """Node indices (k, 4) of the faces of a face set, outward-oriented."""
        fs = self.face_sets[name]
        return self.cells[fs[:, 0][:, None], HEX_FACES[fs[:, 1]]]

    def face_set_points(self, name: str) -> np.ndarray:
        """Sorted unique node indices on a face set."""
        return np.unique(self.face_nodes(name))

    def body_cells(self, body: str) -> np.ndarray:
        """Indices of the cells of one body."""
        return np.flatnonzero(self.cell_body == self.bodies.index(body))

    def transformed(self, R, t) -> "HexMesh":
        """Copy moved rigidly, x -> R x + t (proper rotation R, t [mm]); reference points follow."""
        R = np.asarray(R, float).reshape(3, 3)
        t = np.asarray(t, float).reshape(3)
        if np.linalg.det(R) <= 0:
            raise FEInputError("R", float(np.linalg.det(R)), "a proper rotation (det +1): a reflection inverts the hexahedra")
        refs = {k: ReferencePoint(tuple(R @ np.asarray(v.point) + t), tuple(R @ np.asarray(v.axis)))
                for k, v in self.reference_points.items()}
        return HexMesh(self.points @ R.T + t, self.cells, self.cell_body, self.bodies, self.point_sets, self.face_sets,
                       refs, self.contact_pairs, self.meta)


def merge_meshes(meshes, contact_pairs=(), meta=None) -> HexMesh:
    """One mesh holding the bodies of several meshes (body names must differ); nodes are not shared."""
    pts, cells, body, bodies = [], [], [], []
    psets, fsets, refs, pairs = {}, {}, {}, []
    n0 = c0 = 0
    for m in meshes:
        for b in m.bodies:
            if b in bodies:
                raise FEInputError("bodies", b, "distinct body names in merged meshes")
        pts.append(m.points)
        cells.append(m.cells + n0)
        body.append(m.cell_body + len(bodies))
        bodies.extend(m.bodies)
        psets.update({k: v + n0 for k, v in m.point_sets.items()})
        fsets.update({k: v + np.array([c0, 0]) for k, v in m.face_sets.items()})
        refs.update(m.reference_points)
        pairs.extend(m.contact_pairs)
        n0 += m.n_points
        c0 += m.n_cells
    return HexMesh(np.concatenate(pts), np.concatenate(cells), np.concatenate(body), tuple(bodies), psets, fsets,
                   refs, tuple(pairs) + tuple(contact_pairs), dict(meta or {}))
