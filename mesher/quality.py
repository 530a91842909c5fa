r"""Element quality, volumes and conformity of a hexahedral mesh (vectorized over all elements).

Trilinear map of the reference cube :math:`[-1, 1]^3`, :math:`x(\xi) = \sum_a N_a(\xi) x_a` with
:math:`N_a = \tfrac18 (1 + \xi_a \xi)(1 + \eta_a \eta)(1 + \zeta_a \zeta)`. At the 2×2×2 Gauss points
:math:`\xi = \pm 1/\sqrt3` the Jacobian :math:`J = \partial x / \partial \xi` gives

* the **scaled Jacobian** :math:`\det J / (|J_{:,1}|\,|J_{:,2}|\,|J_{:,3}|)` (1 for a parallelepiped
  with right angles, ≤ 0 for an inverted element) — the reported minimum is over all Gauss points;
* the element **volume** :math:`\sum_g \det J(\xi_g)` (weights 1), exact for trilinear hexahedra
  because :math:`\det J` has degree ≤ 2 in each reference coordinate.

The **aspect ratio** reported is the edge ratio, longest / shortest of the 12 edges.

Conformity: with faces keyed by their sorted node ids, every face of a conforming mesh belongs to
one hexahedron (boundary) or two (interior); a face shared by three or more, a node used by no
element or two nodes at the same place of one body are errors.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from tca.errors import GeometryError

from fem.mesh.hexmesh import HEX_FACES, HexMesh

__all__ = ["Quality", "quality", "check_quality", "element_volumes", "face_counts", "check_conformity", "HEX_EDGES"]

_CORNERS = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                     [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float)
HEX_EDGES = np.array([[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4], [0, 4], [1, 5], [2, 6], [3, 7]])


def _dshape(xi: np.ndarray) -> np.ndarray:
    """Shape-function gradients (g, 8, 3) at reference points xi (g, 3)."""
    a = _CORNERS[None, :, :]
    p = 1.0 + a * xi[:, None, :]
    return 0.125 * a * np.stack([p[..., 1] * p[..., 2], p[..., 0] * p[..., 2], p[..., 0] * p[..., 1]], -1)


_GAUSS = _CORNERS / np.sqrt(3.0)
_DN_GAUSS = _dshape(_GAUSS)
_DN_CORNER = _dshape(_CORNERS)


def _jacobians(X: np.ndarray, dN: np.ndarray) -> np.ndarray:
    """J (m, g, 3, 3) for element coordinates X (m, 8, 3); J[..., i, k] = dx_i/dxi_k."""
    return np.einsum("mai,gak->mgik", X, dN, optimize=True)


def _det(J):
    return (J[..., 0, 0] * (J[..., 1, 1] * J[..., 2, 2] - J[..., 1, 2] * J[..., 2, 1])
            - J[..., 0, 1] * (J[..., 1, 0] * J[..., 2, 2] - J[..., 1, 2] * J[..., 2, 0])
            + J[..., 0, 2] * (J[..., 1, 0] * J[..., 2, 1] - J[..., 1, 1] * J[..., 2, 0]))


def _scaled(J):
    d = _det(J)
    n = np.linalg.norm(J, axis=-2)  # column norms (m, g, 3)
    return d, d / np.prod(n, axis=-1)


@dataclass(frozen=True, eq=False)
class Quality:
    """Per-element quality of a mesh."""

    min_scaled_jacobian: np.ndarray  # (m,) over the 8 Gauss points
    min_corner_scaled_jacobian: np.ndarray  # (m,) over the 8 corners
    min_det: np.ndarray  # (m,) smallest det J at the Gauss points [mm^3]
    aspect_ratio: np.ndarray  # (m,) longest / shortest edge
    volume: np.ndarray  # (m,) [mm^3]

    def summary(self) -> dict:
        return {"min_scaled_jacobian": float(self.min_scaled_jacobian.min()),
                "min_corner_scaled_jacobian": float(self.min_corner_scaled_jacobian.min()),
                "max_aspect_ratio": float(self.aspect_ratio.max()),
                "volume_mm3": float(self.volume.sum())}


def quality(mesh: HexMesh, chunk: int = 200_000) -> Quality:
    """Scaled Jacobians (Gauss points and corners), aspect ratios and volumes of all elements."""
    out = {k: [] for k in ("sj", "sjc", "det", "ar", "vol")}
    for c0 in range(0, mesh.n_cells, chunk):
        X = mesh.points[mesh.cells[c0:c0 + chunk]]
        d, s = _scaled(_jacobians(X, _DN_GAUSS))
        _, sc = _scaled(_jacobians(X, _DN_CORNER))
        e = np.linalg.norm(X[:, HEX_EDGES[:, 1]] - X[:, HEX_EDGES[:, 0]], axis=-1)
        with np.errstate(divide="ignore"):
            out["ar"].append(e.max(1) / e.min(1))
        out["sj"].append(s.min(1))
        out["sjc"].append(sc.min(1))
        out["det"].append(d.min(1))
        out["vol"].append(d.sum(1))
    cat = {k: np.concatenate(v) if v else np.zeros(0) for k, v in out.items()}
    return Quality(cat["sj"], cat["sjc"], cat["det"], cat["ar"], cat["vol"])


def element_volumes(mesh: HexMesh) -> np.ndarray:
    """Volumes of all elements by 2x2x2 Gauss quadrature (exact for trilinear maps) [mm^3]."""
    return quality(mesh).volume


def check_quality(mesh: HexMesh) -> Quality:
    """Quality of a mesh; raises GeometryError naming the element and body if any Jacobian is <= 0."""
    q = quality(mesh)
    bad = np.flatnonzero(~(q.min_det > 0))
    if len(bad):
        i = int(bad[np.argmin(q.min_det[bad])])
        body = mesh.bodies[mesh.cell_body[i]]
        raise GeometryError(body, "inverted element",
                            f"element {i} (0-based) has det J = {q.min_det[i]:.3e} mm^3 at a Gauss point "
                            f"(scaled Jacobian {q.min_scaled_jacobian[i]:.3f}; {len(bad)} element(s) with det J <= 0), "
                            f"centroid {np.round(mesh.points[mesh.cells[i]].mean(0), 4).tolist()} mm")
    return q


def face_counts(mesh: HexMesh):
    """(faces (k, 4) sorted node ids, how many elements hold each, first (cell, local face) of each)."""
    f = mesh.cells[:, HEX_FACES].reshape(-1, 4)
    key = np.sort(f, axis=1)
    uniq, first, cnt = np.unique(key, axis=0, return_index=True, return_counts=True)
    return uniq, cnt, np.stack([first // 6, first % 6], -1)


def check_conformity(mesh: HexMesh, tol: float = 1e-9) -> dict:
    """Face-sharing and node checks; raises GeometryError on a non-conforming mesh, else returns counts."""
    _, cnt, where = face_counts(mesh)
    if np.any(cnt > 2):
        i = int(np.flatnonzero(cnt > 2)[0])
        raise GeometryError(mesh.bodies[mesh.cell_body[where[i, 0]]], "non-conforming mesh",
                            f"a face of element {where[i, 0]} is shared by {cnt[i]} elements")
    used = np.zeros(mesh.n_points, bool)
    used[mesh.cells.ravel()] = True
    if not used.all():
        raise GeometryError("mesh", "unused nodes", f"{int((~used).sum())} node(s) belong to no element")
    dup = 0
    for b in range(len(mesh.bodies)):
        nodes = np.unique(mesh.cells[mesh.cell_body == b])
        pairs = cKDTree(mesh.points[nodes]).query_pairs(tol, output_type="ndarray")
        if len(pairs):
            p = mesh.points[nodes[pairs[0, 0]]]
            raise GeometryError(mesh.bodies[b], "duplicate nodes",
                                f"{len(pairs)} pair(s) of distinct nodes closer than {tol:g} mm, e.g. at {p.tolist()}")
        dup += len(pairs)
    return {"boundary_faces": int(np.sum(cnt == 1)), "interior_faces": int(np.sum(cnt == 2)), "duplicate_nodes": dup}
