"""The constraints of the contact pairs: gaps, gap gradients, areas, penalties, candidates and seed.

Geometry (small sliding, from the undeformed mesh as the caller positioned it). A point x_s of the slave
surface is projected on the bilinear master faces, x_p = sum_b N_b(xi, eta) x_b, with the outward
master normal n; its linearized normal gap is

    g = g0 + n . (u(x_s) - sum_b N_b u_b),    g0 = (x_s - x_p) . n.

Constraints, each with a compressive normal force lambda >= 0 acting as G^T lambda (G the
gradient of the gaps):

- ``quadrature = 0``, node-to-surface: one per slave node; x_s is the node, g_a its gap, A_a its
  tributary area (integral of its shape function over the slave faces).
- ``quadrature = n`` (default 2) and ``points = 'gauss'`` (default, issue 14): one per Gauss point
  q of the n x n rule of each slave face, with its own gap g_q, area A_q = w_q |J_q| and penalty
  force lambda_q. The slave node a receives F_a = sum_q N_a(x_q) lambda_q. The contact edge is
  resolved to a Gauss point instead of a node: at 3 elements per Hertz half-width the peak
  pressure is within 1 % (line and point), where the averaged nodal gaps give +7.8 % and +5.8 %
  (a node at the edge cannot open while part of its support is closed, and the load moves
  inward). There are more constraints than normal DOFs, so lambda_q alternates from point to
  point (the tractions themselves are not used); the nodal forces F_a are smooth.
- ``quadrature = n`` and ``points = 'nodes'`` (issue 6), segment-to-segment with averaged gaps:
  one per slave node, g_a = int N_a g dA / A_a evaluated at the Gauss points. On non-matching
  meshes this removes most of the node-to-surface pressure oscillation (Hertz line, master/slave
  face sizes 0.67: peak +10 % node-to-surface, +2 % averaged); a +-4 % ripple remains because the
  master faces are not segmented.

The master must be about as fine as the slave (``MAX_MASTER_COARSENESS``). The penalty law is
lambda = k <-g>, k = eps A, eps = factor * E / h [MPa/mm] with h the thickness of the slave element
under the point: the penalty is ``factor`` times the normal stiffness of that element.

Pressure (``ContactSet.pressure``). Node constraints: p_a = lambda_a / A_a. Gauss-point
constraints: the L2 projection of the traction onto the slave's nodal basis, M p = F with the
consistent surface mass M_ab = int N_a N_b dA (``surface_mass``), solved by the lumped start
p0 = F / D (D = M 1, the tributary areas) and one Jacobi step,

    p = max(0, p0 + D^-1 (F - M p0))      where p0 > 0, else 0.

The lumped p0 is a weighted mean of the pressure over the node's support and smooths the peak
by O(h^2) (measured at 3 elements per half-width: Hertz line -1.8 %, point -3.2 %; with the step
-0.3 %, -0.2 %); the step removes that leading term, while the exact solve of M p = F amplifies
the node-to-node variation of the forces (measured +45 % at the Hertz line peak on the averaged-
gap forces). The recovered peak converges from above and
the lumped one from below on the gear model (docs/contact_pressure.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree

from fem.assembly import face_node_areas
from fem.constraints import known_names
from fem.contact.faces import bilinear, project_to_faces, surface_mass
from fem.errors import FEInputError
from fem.mesh.hexmesh import HEX_FACES, HexMesh
from fem.model import ContactPair

__all__ = ["MAX_MASTER_COARSENESS", "ContactSet", "contact_set"]

_OPPOSITE = np.array([1, 0, 4, 5, 2, 3])


@dataclass(frozen=True, eq=False)
class ContactSet:
    """One contact constraint per slave node of each pair, projected on the pair's master."""

    pair: np.ndarray  # (k,) index into the model's contact pairs
    node: np.ndarray  # (k,) slave node
    area: np.ndarray  # (k,) tributary area A_a [mm^2]
    normal: np.ndarray  # (k, 3) outward master normal (averaged over the node's Gauss points)
    gap0: np.ndarray  # (k,) initial normal gap [mm]
    penalty: np.ndarray  # (k,) eps [MPa/mm]
    G: sp.csr_matrix  # (k, 3n) gap gradient
    candidate: np.ndarray  # (k,) bool, gap0 < search_gap, or seed
    seed: np.ndarray  # (k,) bool, initial active set
    shape: sp.csr_matrix | None = None  # (n, k) N_a(x_q) of the constraint points (nodes: 1 at the node)
    mass: sp.csr_matrix | None = None  # (n, n) consistent slave-surface mass int N_a N_b dA (Gauss-point constraints)

    @property
    def stiffness(self) -> np.ndarray:
        """Penalty stiffness eps * A per constraint [N/mm]."""
        return self.penalty * self.area

    def to_nodes(self, values: np.ndarray, n_nodes: int, rows=None) -> np.ndarray:
        """Nodal field of per-constraint values (area-weighted where a node is in two pairs; nan elsewhere)."""
        rows = np.arange(len(self.area)) if rows is None else rows
        if self.shape is None:
            num = np.bincount(self.node[rows], weights=self.area[rows] * values[rows], minlength=n_nodes)
            den = np.bincount(self.node[rows], weights=self.area[rows], minlength=n_nodes)
        else:
            R = self.shape[:n_nodes][:, rows]
            num, den = R @ (self.area[rows] * values[rows]), R @ self.area[rows]
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(den > 0, num / den, np.nan)

    def nodal_forces(self, lam: np.ndarray, n_nodes: int, rows=None) -> np.ndarray:
        """Normal contact force per slave node F_a = sum_q N_a(x_q) lambda_q [N] (n,)."""
        rows = np.arange(len(self.area)) if rows is None else rows
        return self.shape[:n_nodes][:, rows] @ lam[rows]

    def pressure(self, lam: np.ndarray, n_nodes: int, rows=None) -> np.ndarray:
        """Nodal contact pressure [MPa] (n,), nan off the slave surfaces (module docstring, "Pressure").

        Node constraints: lambda_a / A_a. Gauss-point constraints: the lumped projection
        p0 = F / D of the nodal forces, corrected by one Jacobi step of the consistent
        projection M p = F, p = max(0, p0 + D^-1 (F - M p0)) where p0 > 0.
        """
        if self.mass is None:
            rows = np.arange(len(self.area)) if rows is None else rows
            return self.to_nodes(lam / self.area, n_nodes, rows)
        F = self.nodal_forces(lam, n_nodes, rows)
        M = self.mass[:n_nodes][:, :n_nodes]
        D = np.asarray(M.sum(axis=1)).ravel()
        with np.errstate(invalid="ignore", divide="ignore"):
            p0 = np.where(D > 0, F / D, 0.0)
            p = np.where(p0 > 0, np.maximum(p0 + (F - M @ p0) / D, 0.0), 0.0)
            return np.where(D > 0, p, np.nan)


def _faces(mesh: HexMesh, name: str, field: str) -> np.ndarray:
    if name not in mesh.face_sets:
        raise FEInputError(field, name, f"a face set of the mesh ({known_names(mesh.face_sets)})")
    fs = mesh.face_sets[name]
    if len(fs) == 0:
        raise FEInputError(field, name, "a non-empty face set")
    return fs



def _slave_points(mesh: HexMesh, fs: np.ndarray, order: int):
    """Contact points of slave faces: nodes (order 0) or order x order Gauss points per face.

    Returns slave nodes (k, s), weights (k, s), points (k, 3), areas (k,), outward slave normals
    (k, 3) and thickness h (k,) of the slave element below [mm].
    """
    sf = mesh.cells[fs[:, 0][:, None], HEX_FACES[fs[:, 1]]]  # (f, 4)
    X = mesh.points[sf]
    opp = mesh.cells[fs[:, 0][:, None], HEX_FACES[_OPPOSITE[fs[:, 1]]]]
    h_face = np.linalg.norm(X.mean(1) - mesh.points[opp].mean(1), axis=1)
    if order == 0:
        nodes, inv = np.unique(sf, return_inverse=True)
        inv = inv.ravel()
        w = face_node_areas(mesh.points, sf).ravel()
        area = np.bincount(inv, weights=w, minlength=len(nodes))
        fn = np.cross(X[:, 2] - X[:, 0], X[:, 3] - X[:, 1])  # area-weighted outward normal
        ns = np.stack([np.bincount(inv, weights=np.repeat(fn[:, c], 4), minlength=len(nodes)) for c in range(3)], 1)
        h = np.bincount(inv, weights=w * np.repeat(h_face, 4), minlength=len(nodes)) / area
        return nodes[:, None], np.ones((len(nodes), 1)), mesh.points[nodes], area, ns / np.linalg.norm(ns, axis=1, keepdims=True), h
    g, wg = np.polynomial.legendre.leggauss(order)
    xi, eta = (a.ravel() for a in np.meshgrid(g, g, indexing="ij"))
    wq = np.outer(wg, wg).ravel()
    N, dxi, deta = bilinear(xi, eta)  # (q, 4)
    pts = np.einsum("qa,fai->fqi", N, X)
    n = np.cross(np.einsum("qa,fai->fqi", dxi, X), np.einsum("qa,fai->fqi", deta, X))
    dA = np.linalg.norm(n, axis=-1)
    q = len(wq)
    return (np.repeat(sf, q, axis=0), np.tile(N, (len(sf), 1)), pts.reshape(-1, 3), (dA * wq).ravel(),
            (n / dA[..., None]).reshape(-1, 3), np.repeat(h_face, q))



MAX_MASTER_COARSENESS = 1.3


def _check_master_resolution(mesh, pair, fs, fm):
    """Refuse a master surface much coarser than the slave in the contact zone (faces fs, fm).

    With one constraint per slave node, a fine slave on a coarse master over-constrains the
    master and the pressure oscillates (measured, Hertz point contact, 2x2 averaged gaps: peak
    +2 % at a master/slave face-size ratio of 1.25, +7 % at 1.5, +29 % at 2).
    """
    if len(fs) == 0 or len(fm) == 0:
        return
    size_s = np.sqrt(face_node_areas(mesh.points, mesh.cells[fs[:, 0][:, None], HEX_FACES[fs[:, 1]]]).sum(1))
    size_m = np.sqrt(face_node_areas(mesh.points, mesh.cells[fm[:, 0][:, None], HEX_FACES[fm[:, 1]]]).sum(1))
    ratio = float(np.median(size_m) / np.median(size_s))
    if ratio > MAX_MASTER_COARSENESS:
        raise FEInputError(f"contacts[{pair.name!r}]", (pair.slave, pair.master),
                         f"a master surface about as fine as the slave in the contact zone (face-size ratio <= {MAX_MASTER_COARSENESS})",
                         f"measured {ratio:.2f}: exchange slave and master, or refine the master")


def contact_set(mesh: HexMesh, pairs: tuple[ContactPair, ...], E_cell: np.ndarray, factor: float, order: int = 2,
                points: str = "nodes") -> ContactSet:
    """One constraint per slave node of every pair: gaps, gap gradients, normals, areas, penalties.

    order 0: the node projected on the master (node-to-surface); order n >= 2: the n x n Gauss
    points of the slave faces projected on the master, their gaps averaged per node with weights
    N_a dA (segment-to-segment).
    """
    parts = []
    n_dof = 3 * mesh.n_points
    for ip, pair in enumerate(pairs):
        fs = _faces(mesh, pair.slave, f"contacts[{pair.name!r}].slave")
        fm = _faces(mesh, pair.master, f"contacts[{pair.name!r}].master")
        sb, mb = mesh.cell_body[fs[:, 0]], mesh.cell_body[fm[:, 0]]
        if len(np.unique(sb)) != 1 or len(np.unique(mb)) != 1 or sb[0] == mb[0]:
            raise FEInputError(f"contacts[{pair.name!r}]", (pair.slave, pair.master), "slave and master face sets each on one body, two different bodies")
        snodes, sw, xs0, area, ns, h = _slave_points(mesh, fs, order)
        E = min(E_cell[fs[:, 0]].min(), E_cell[fm[:, 0]].min())
        # projection on the master faces: nearest face centres first
        mf_nodes = mesh.cells[fm[:, 0][:, None], HEX_FACES[fm[:, 1]]]
        Xm = mesh.points[mf_nodes]
        npt = len(xs0)
        kq = min(12, len(fm))
        _, cand = cKDTree(Xm.mean(1)).query(xs0, k=kq)
        cand = cand.reshape(npt, kq)
        xs = np.repeat(xs0, kq, axis=0)
        xi, eta, xp = project_to_faces(xs, Xm[cand.ravel()])
        inside = (np.abs(xi) <= 1.0 + 1e-6) & (np.abs(eta) <= 1.0 + 1e-6)
        d = np.where(inside, np.linalg.norm(xs - xp, axis=1), np.inf).reshape(npt, kq)
        best = np.argmin(d, axis=1)
        sel = np.arange(npt) * kq + best
        ok = np.isfinite(d[np.arange(npt), best])
        face = cand.ravel()[sel]
        N, dxi, deta = bilinear(xi[sel], eta[sel])
        nm = np.cross(np.einsum("pa,pai->pi", dxi, Xm[face]), np.einsum("pa,pai->pi", deta, Xm[face]))
        nm /= np.linalg.norm(nm, axis=1, keepdims=True)
        ok &= np.einsum("ij,ij->i", nm, ns) < -0.5  # the surfaces face each other
        g0 = np.einsum("ij,ij->i", xs0 - xp[sel], nm)
        keep = np.flatnonzero(ok)
        zone = keep[g0[keep] < pair.search_gap]
        if order:
            zone_slave = np.unique(zone // (order * order))  # Gauss points are stored face by face
        else:
            sf = mesh.cells[fs[:, 0][:, None], HEX_FACES[fs[:, 1]]]
            zone_slave = np.flatnonzero(np.isin(sf, snodes[zone, 0]).any(axis=1))
        _check_master_resolution(mesh, pair, fs[zone_slave], fm[np.unique(face[zone])])
        snodes, sw, xs0, area, nm, g0 = snodes[keep], sw[keep], xs0[keep], area[keep], nm[keep], g0[keep]
        eps = factor * E / h[keep]
        mnodes, N = mf_nodes[face[keep]], N[keep]
        rows = np.repeat(np.arange(len(keep)), 3 * (snodes.shape[1] + 4))
        cols = np.concatenate([3 * snodes[:, :, None] + np.arange(3), 3 * mnodes[:, :, None] + np.arange(3)], axis=1).ravel()
        vals = np.concatenate([sw[:, :, None] * nm[:, None, :], -N[:, :, None] * nm[:, None, :]], axis=1).ravel()
        G = sp.csr_matrix((vals, (rows, cols)), shape=(len(keep), n_dof))
        shape = mass = None
        if order > 0 and points == "gauss":
            shape = sp.csr_matrix((sw.ravel(), (snodes.ravel(), np.repeat(np.arange(len(keep)), snodes.shape[1]))),
                                  shape=(mesh.n_points, len(keep)))
            mass = surface_mass(mesh.points, mesh.cells[fs[:, 0][:, None], HEX_FACES[fs[:, 1]]])
            snodes = snodes[np.arange(len(keep)), np.argmax(sw, axis=1)][:, None]
        elif order > 0:
            # averaged gap per slave node: g_a = int N_a g dA / int N_a dA over the Gauss points
            nodes, inv = np.unique(snodes, return_inverse=True)
            M = sp.csr_matrix(((sw * area[:, None]).ravel(), (inv.ravel(), np.repeat(np.arange(len(keep)), 4))),
                              shape=(len(nodes), len(keep)))
            A = np.asarray(M.sum(axis=1)).ravel()
            Dinv = sp.diags(1.0 / A)
            G = (Dinv @ M @ G).tocsr()
            g0, eps = Dinv @ (M @ g0), Dinv @ (M @ eps)
            nm = Dinv @ (M @ nm)
            nm /= np.linalg.norm(nm, axis=1, keepdims=True)
            snodes, xs0, area = nodes[:, None], mesh.points[nodes], A
        seed = np.zeros(len(g0), bool)
        if len(g0) and pair.contact_point is not None:
            dist = np.linalg.norm(xs0 - np.asarray(pair.contact_point), axis=1)
            seed[dist <= max(pair.contact_radius, dist.min())] = True
        elif len(g0):
            seed[g0 <= g0.min() + 1e-9] = True
        if shape is None:
            shape = sp.csr_matrix((np.ones(len(g0)), (snodes[:, 0], np.arange(len(g0)))), shape=(mesh.n_points, len(g0)))
        parts.append(dict(pair=np.full(len(g0), ip), node=snodes[:, 0], area=area, normal=nm, gap0=g0, penalty=eps, G=G,
                          candidate=(g0 < pair.search_gap) | seed, seed=seed, shape=shape, mass=mass))
    shapes = {"pair": (0,), "node": (0,), "area": (0,), "normal": (0, 3), "gap0": (0,), "penalty": (0,), "candidate": (0,), "seed": (0,)}
    cat = {key: np.concatenate([p[key] for p in parts]) if parts else np.zeros(shp) for key, shp in shapes.items()}
    G = sp.vstack([p["G"] for p in parts], format="csr") if parts else sp.csr_matrix((0, n_dof))
    shape = sp.hstack([p["shape"] for p in parts], format="csr") if parts else sp.csr_matrix((mesh.n_points, 0))
    masses = [p["mass"] for p in parts if p["mass"] is not None]
    mass = None if not masses else sum(masses[1:], masses[0]).tocsr()
    return ContactSet(cat["pair"].astype(np.int64), cat["node"].astype(np.int64), cat["area"], cat["normal"], cat["gap0"],
                      cat["penalty"], G, cat["candidate"].astype(bool), cat["seed"].astype(bool), shape, mass)
