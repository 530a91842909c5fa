"""Penalty contact between slave and master surfaces, solved on the Schur complement of the gaps.

Geometry (small sliding, from the undeformed, TCA-positioned mesh). A point x_s of the slave
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

Patch (``contact_patch``). The Hertz-equivalent contact ellipse of nodal forces F_a at x_a: the
resultant P, the centre c = sum F x / P, and the tangential second moments mu = sum F (t.(x - c))^2 / P
along the principal directions t. A semi-ellipsoidal pressure has int x^2 p dA / P = a^2 / 5, an
elliptic line pressure a^2 / 4 across (uniform along: L^2 / 12 = l^2 / 3 with l the half-length),
so a = sqrt(5 mu) (point), b = sqrt(4 mu) (line). Integral quantities of the forces, they do not
jump by an element when the edge of the contact passes a node.

Reduced problem (``fem.analysis``). The reduced stiffness bordered by the gap rows of the k
candidate nodes is factored once with its Schur complement on the free rigid DOFs F and the gap
rows, which gives directly

    W = G K_RR^-1 G^T         (gap compliance with the free rigid DOFs clamped),
    B = G K_RR^-1 K_RF - G_F  (gap change per free rigid DOF, sign as below),
    H = K_FF - K_FR K_RR^-1 K_RF,
    g^ = g0 + G u_p + G K_RR^-1 f_R,   f^_F = f_F - K_FR K_RR^-1 f_R,

so that the gaps and the equilibrium of the free rigid DOFs read

    g = g^ + W lambda - B u_F,         H u_F + B^T lambda = f^_F.

H is singular for a body that is free before contact closes (a free planet); the bordered system
on an active set A,

    [ W_AA + K_A^-1   -B_A ] [lambda_A]   [ -g^_A ]
    [ -B_A^T          -H   ] [  u_F   ] = [ -f^_F ],

is regular once the active contacts hold the free rotations. Primal-dual active set iteration
(semismooth Newton on the penalty law): A <- {g < 0} until A repeats. Each iteration costs a
dense solve of the size of A: no sparse refactorization. The penalty may then be raised (no
refactorization either) until the largest penetration is below the tolerance, and the peak
pressure is compared with a solve at twice the penalty.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from scipy.spatial import cKDTree

from fem.mesh.hexmesh import HEX_FACES, HexMesh
from fem.errors import FEConvergenceError, FEError, FEInputError

try:
    from threadpoolctl import threadpool_limits
except ImportError:  # pragma: no cover - optional: without it the dense solves use the BLAS default threads
    threadpool_limits = None

from fem.assembly import face_node_areas
from fem.constraints import known_names
from fem.model import ContactOptions, ContactPair

__all__ = ["ContactSet", "contact_set", "ActiveSetSolution", "active_set", "penalty_active_set", "bilinear",
           "project_to_faces", "surface_mass", "ContactPatch", "contact_patch"]

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


def bilinear(xi, eta):
    """Shape functions of a 4-node face and their derivatives at (xi, eta): N, dN/dxi, dN/deta (..., 4)."""
    N = 0.25 * np.stack([(1 - xi) * (1 - eta), (1 + xi) * (1 - eta), (1 + xi) * (1 + eta), (1 - xi) * (1 + eta)], -1)
    dxi = 0.25 * np.stack([-(1 - eta), (1 - eta), (1 + eta), -(1 + eta)], -1)
    deta = 0.25 * np.stack([-(1 - xi), -(1 + xi), (1 + xi), (1 - xi)], -1)
    return N, dxi, deta


def project_to_faces(xs: np.ndarray, X: np.ndarray, iters: int = 12, limit: float = 2.0):
    """Closest-point projection of points xs (p, 3) on bilinear faces X (p, 4, 3): xi, eta, x_p.

    The face coordinates are kept in [-limit, limit] (1: on the face itself; 2: its extension,
    which lets the contact search slide across face boundaries)."""
    xi = np.zeros(len(xs))
    eta = np.zeros(len(xs))
    for _ in range(iters):
        N, dxi, deta = bilinear(xi, eta)
        x = np.einsum("pa,pai->pi", N, X)
        t1 = np.einsum("pa,pai->pi", dxi, X)
        t2 = np.einsum("pa,pai->pi", deta, X)
        r = x - xs
        a11, a12, a22 = (t1 * t1).sum(1), (t1 * t2).sum(1), (t2 * t2).sum(1)
        b1, b2 = -(t1 * r).sum(1), -(t2 * r).sum(1)
        det = a11 * a22 - a12**2
        xi = np.clip(xi + (a22 * b1 - a12 * b2) / det, -limit, limit)
        eta = np.clip(eta + (a11 * b2 - a12 * b1) / det, -limit, limit)
    N, dxi, deta = bilinear(xi, eta)
    return xi, eta, np.einsum("pa,pai->pi", N, X)


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


def surface_mass(points: np.ndarray, faces: np.ndarray) -> sp.csr_matrix:
    """Consistent mass M_ab = int N_a N_b dA of bilinear faces (f, 4) [mm^2], 2 x 2 Gauss points; (n, n)."""
    g, wg = np.polynomial.legendre.leggauss(2)
    xi, eta = (a.ravel() for a in np.meshgrid(g, g, indexing="ij"))
    N, dxi, deta = bilinear(xi, eta)
    X = points[faces]
    dA = np.linalg.norm(np.cross(np.einsum("qa,fai->fqi", dxi, X), np.einsum("qa,fai->fqi", deta, X)), axis=-1)
    Me = np.einsum("fq,q,qa,qb->fab", dA, np.outer(wg, wg).ravel(), N, N)
    rows = np.repeat(faces, 4, axis=1).ravel()
    cols = np.tile(faces, (1, 4)).ravel()
    n = len(points)
    return sp.csr_matrix((Me.ravel(), (rows, cols)), shape=(n, n))


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


@dataclass(frozen=True)
class ContactPatch:
    """Hertz-equivalent contact patch of nodal forces (module docstring, "Patch"): force [N], centre [mm],
    semi-axes a >= b [mm] and their unit directions."""

    force: float
    centre: tuple[float, float, float]
    semi_axes: tuple[float, float]
    directions: tuple[tuple[float, float, float], tuple[float, float, float]]


PATCH_FACTORS = {"point": (5.0, 5.0), "line": (3.0, 4.0)}


def contact_patch(points: np.ndarray, forces: np.ndarray, normal, centre=None, kind: str = "point", major=None) -> ContactPatch:
    """Semi-axes of the Hertz pressure with the same resultant and second moments as the nodal forces.

    points (n, 3) [mm], forces (n,) >= 0 [N], normal (3,) the common normal; ``centre`` [mm]
    (default the force centroid; give the symmetry point of a half or quarter model); ``kind``
    'point' (semi-ellipsoid: a^2 = 5 mu) or 'line' (semi-ellipse across, uniform along: b^2 = 4 mu,
    half-length^2 = 3 mu), mu the second moments about the centre along the axes. The axes are the
    eigenvectors of the tangential second-moment tensor, or ``major`` (3,) and n x major when given.
    """
    if kind not in PATCH_FACTORS:
        raise FEInputError("kind", kind, "'point' or 'line'")
    F = np.clip(np.asarray(forces, float), 0.0, None)
    P = float(F.sum())
    if P <= 0.0:
        nan = float("nan")
        return ContactPatch(0.0, (nan, nan, nan), (0.0, 0.0), ((nan,) * 3, (nan,) * 3))
    x = np.asarray(points, float)
    c = (F @ x) / P if centre is None else np.asarray(centre, float)
    n = np.asarray(normal, float) / np.linalg.norm(normal)
    d = x - c
    d -= np.outer(d @ n, n)  # tangential offsets
    S = np.einsum("p,pi,pj->ij", F, d, d) / P
    if major is None:
        mu, vec = np.linalg.eigh(S)  # ascending; the smallest is along the normal
        e1, e2 = vec[:, 2], vec[:, 1]
    else:
        e1 = np.asarray(major, float) - (np.asarray(major, float) @ n) * n
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(n, e1)
    fa, fb = PATCH_FACTORS[kind]
    a, b = np.sqrt(fa * max(float(e1 @ S @ e1), 0.0)), np.sqrt(fb * max(float(e2 @ S @ e2), 0.0))
    return ContactPatch(P, tuple(float(v) for v in c), (float(a), float(b)),
                        (tuple(float(v) for v in e1), tuple(float(v) for v in e2)))


@dataclass(frozen=True, eq=False)
class ActiveSetSolution:
    """Contact forces lambda [N], free rigid DOFs, gaps [mm], active set, iterations, penalty scale."""

    lam: np.ndarray
    u_free: np.ndarray
    gap: np.ndarray
    active: np.ndarray
    iterations: int
    scale: float = 1.0
    penalty_change: float = float("nan")


def _solve_set(W, B, H, ghat, fhat, k, A, h_scale):
    a = np.flatnonzero(A)
    nF = len(fhat)
    lam = np.zeros(len(ghat))
    if len(a):
        P = W[np.ix_(a, a)] + np.diag(1.0 / k[a])
        try:
            cf = sla.cho_factor(P)
        except np.linalg.LinAlgError:
            raise FEError("contact compliance matrix is not positive definite on the active set") from None
        Ba = B[a]
        Z = sla.cho_solve(cf, np.column_stack([Ba, ghat[a]])) if nF else sla.cho_solve(cf, ghat[a][:, None])
    else:
        Ba = np.zeros((0, nF))
        Z = np.zeros((0, nF + 1))
    uF = np.zeros(nF)
    if nF:
        Hs = H + Ba.T @ Z[:, :nF]
        # a free rigid DOF is held if its condensed stiffness is not round-off of its own
        # stiffness with everything else clamped (h_scale = diag of the reduced K there)
        loose = np.diag(Hs) <= 1e-9 * h_scale
        if loose.any():
            raise FEError(
                f"free rigid DOF(s) {np.flatnonzero(loose).tolist()} are not held by any active contact: "
                "the contact does not close (check the contact seed, the search gap and the load direction)"
            )
        uF = np.linalg.solve(Hs, fhat + Ba.T @ Z[:, nF])
    if len(a):
        # lambda_A = P^-1 (B_A u_F - g^_A)
        lam[a] = (Z[:, :nF] @ uF if nF else 0.0) - Z[:, -1]
    return lam, uF


def active_set(W, B, H, ghat, fhat, k, active0, max_iterations: int, h_scale) -> ActiveSetSolution:
    """Primal-dual active-set iteration of the penalty contact problem (see module docstring)."""
    A = np.asarray(active0, bool).copy()
    seen = {A.tobytes()}
    for it in range(1, max_iterations + 1):
        lam, uF = _solve_set(W, B, H, ghat, fhat, k, A, h_scale)
        g = ghat + W @ lam - (B @ uF if len(uF) else 0.0)
        A_new = g < 0.0
        changed = A_new != A
        if not changed.any():
            return ActiveSetSolution(lam, uF, g, A, it)
        viol = float(np.abs(g[changed]).max())  # [mm] gap of the nodes that switch
        key = A_new.tobytes()
        if key in seen:
            raise FEConvergenceError("contact active set", "a repeated set (cycling)", viol, it)
        seen.add(key)
        A = A_new
    raise FEConvergenceError("contact active set", f"{int(changed.sum())} nodes still switching", viol, max_iterations)


def penalty_active_set(W, B, H, ghat, fhat, k, area, active0, opts: ContactOptions, h_scale, peak=None) -> ActiveSetSolution:
    """Active set, with the penalty raised until penetration <= tolerance, then the doubling check.

    ``peak(lam)`` [MPa]: the peak pressure the doubling check compares (default max lambda / area)."""
    peak = peak or (lambda lam: float(np.max(lam / area)))
    # the dense active-set matrices are small (hundreds of rows): threaded BLAS only adds synchronization,
    # which on a loaded machine costs seconds per Cholesky factorization (measured 0.3 s against 0.1 ms at 150 rows)
    with threadpool_limits(1, user_api="blas") if threadpool_limits else contextlib.nullcontext():
        return _penalty_active_set(W, B, H, ghat, fhat, k, area, active0, opts, h_scale, peak)


def _penalty_active_set(W, B, H, ghat, fhat, k, area, active0, opts, h_scale, peak) -> ActiveSetSolution:
    scale = 1.0
    sol = active_set(W, B, H, ghat, fhat, k, active0, opts.max_iterations, h_scale)
    pen = float(np.max(-sol.gap[sol.active], initial=0.0))
    raises = 0
    while pen > opts.max_penetration:
        raises += 1
        if raises > 12:
            raise FEConvergenceError("penalty penetration", f"max_penetration = {opts.max_penetration} mm", pen, raises)
        scale *= max(2.0, 1.5 * pen / opts.max_penetration)
        sol = active_set(W, B, H, ghat, fhat, scale * k, sol.active, opts.max_iterations, h_scale)
        pen = float(np.max(-sol.gap[sol.active], initial=0.0))
    change = float("nan")
    if opts.penalty_check and sol.active.any():
        for _ in range(8):
            sol2 = active_set(W, B, H, ghat, fhat, 2.0 * scale * k, sol.active, opts.max_iterations, h_scale)
            p1, p2 = peak(sol.lam), peak(sol2.lam)
            change = abs(p2 - p1) / p1
            if change < opts.penalty_check_tol:
                break
            scale, sol = 2.0 * scale, sol2
        else:
            raise FEConvergenceError("penalty doubling check", f"penalty_check_tol = {opts.penalty_check_tol}", change, 8)
    return ActiveSetSolution(sol.lam, sol.u_free, sol.gap, sol.active, sol.iterations, scale, change)
