"""Node-to-surface penalty contact, solved on the Schur complement of the contact DOFs.

Geometry (small sliding, from the undeformed, TCA-positioned mesh). Each slave node x_s is
projected on the bilinear master faces, x_p = sum_a N_a(xi, eta) x_a, with the outward master
normal n. The linearized normal gap and its gradient G (one row per slave node) are

    g = g0 + n . (u_s - sum_a N_a u_a),    g0 = (x_s - x_p) . n,

and a compressive nodal contact force lambda >= 0 acts as G^T lambda. The penalty law is
lambda = k <-g>, k = eps A_s: A_s the slave node's tributary area (integral of its shape
function over the slave faces), eps = factor * E / h [MPa/mm] with h the thickness of the slave
element under the node: the penalty is ``factor`` times the normal stiffness of that element.
The nodal pressure is p = lambda / A_s and the penetration of an active node is p / eps.

Reduced problem. With the stiffness factored once and condensed on the candidate contact DOFs
C' and the free rigid DOFs F (``fem.linsolve``), S u_C = f~_C + G_C^T lambda, and eliminating
C' by a dense Cholesky factor of S_11 (SPD: the rigid DOFs are in F):

    g    = g^ + W lambda - B u_F,        W = G_1 S_11^-1 G_1^T,  B = G_1 S_11^-1 S_1F - G_F,
    H u_F + B^T lambda = f^_F,           H = S_FF - S_F1 S_11^-1 S_1F,
    g^ = g0 + G u_p + G_1 S_11^-1 f~_1,  f^_F = f~_F - S_F1 S_11^-1 f~_1.

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

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from scipy.spatial import cKDTree

from mesher.hexmesh import HEX_FACES, HexMesh
from tca.errors import ConvergenceError, GearfeError, InputError

from .assembly import face_node_areas
from .model import ContactOptions, ContactPair

__all__ = ["ContactSet", "contact_set", "ActiveSetSolution", "active_set", "penalty_active_set"]

_OPPOSITE = np.array([1, 0, 4, 5, 2, 3])


@dataclass(frozen=True, eq=False)
class ContactSet:
    """All slave nodes of all pairs that project on their master surface."""

    pair: np.ndarray  # (k,) index into the model's contact pairs
    node: np.ndarray  # (k,) slave node
    area: np.ndarray  # (k,) tributary area [mm^2]
    normal: np.ndarray  # (k, 3) outward master normal
    point: np.ndarray  # (k, 3) projection on the master surface [mm]
    gap0: np.ndarray  # (k,) initial normal gap [mm]
    penalty: np.ndarray  # (k,) eps [MPa/mm]
    G: sp.csr_matrix  # (k, 3n) gap gradient
    candidate: np.ndarray  # (k,) bool, gap0 < search_gap
    seed: np.ndarray  # (k,) bool, initial active set

    @property
    def stiffness(self) -> np.ndarray:
        """Penalty stiffness eps * A per node [N/mm]."""
        return self.penalty * self.area


def _faces(mesh: HexMesh, name: str, field: str) -> np.ndarray:
    if name not in mesh.face_sets:
        known = sorted(mesh.face_sets)
        shown = ", ".join(known[:12]) + (" ..." if len(known) > 12 else "")
        raise InputError(field, name, f"a face set of the mesh ({shown})")
    fs = mesh.face_sets[name]
    if len(fs) == 0:
        raise InputError(field, name, "a non-empty face set")
    return fs


def _bilinear(xi, eta):
    N = 0.25 * np.stack([(1 - xi) * (1 - eta), (1 + xi) * (1 - eta), (1 + xi) * (1 + eta), (1 - xi) * (1 + eta)], -1)
    dxi = 0.25 * np.stack([-(1 - eta), (1 - eta), (1 + eta), -(1 + eta)], -1)
    deta = 0.25 * np.stack([-(1 - xi), -(1 + xi), (1 + xi), (1 - xi)], -1)
    return N, dxi, deta


def _project(xs: np.ndarray, X: np.ndarray, iters: int = 12):
    """Closest-point projection of points xs (p, 3) on bilinear faces X (p, 4, 3): xi, eta, x_p."""
    xi = np.zeros(len(xs))
    eta = np.zeros(len(xs))
    for _ in range(iters):
        N, dxi, deta = _bilinear(xi, eta)
        x = np.einsum("pa,pai->pi", N, X)
        t1 = np.einsum("pa,pai->pi", dxi, X)
        t2 = np.einsum("pa,pai->pi", deta, X)
        r = x - xs
        a11, a12, a22 = (t1 * t1).sum(1), (t1 * t2).sum(1), (t2 * t2).sum(1)
        b1, b2 = -(t1 * r).sum(1), -(t2 * r).sum(1)
        det = a11 * a22 - a12**2
        xi = np.clip(xi + (a22 * b1 - a12 * b2) / det, -2.0, 2.0)
        eta = np.clip(eta + (a11 * b2 - a12 * b1) / det, -2.0, 2.0)
    N, dxi, deta = _bilinear(xi, eta)
    return xi, eta, np.einsum("pa,pai->pi", N, X)


def contact_set(mesh: HexMesh, pairs: tuple[ContactPair, ...], E_cell: np.ndarray, factor: float) -> ContactSet:
    """Project the slave nodes of every pair on its master faces; gaps, normals, areas, penalties."""
    parts = []
    n_dof = 3 * mesh.n_points
    for ip, pair in enumerate(pairs):
        fs = _faces(mesh, pair.slave, f"contacts[{pair.name!r}].slave")
        fm = _faces(mesh, pair.master, f"contacts[{pair.name!r}].master")
        sb, mb = mesh.cell_body[fs[:, 0]], mesh.cell_body[fm[:, 0]]
        if len(np.unique(sb)) != 1 or len(np.unique(mb)) != 1 or sb[0] == mb[0]:
            raise InputError(f"contacts[{pair.name!r}]", (pair.slave, pair.master), "slave and master face sets each on one body, two different bodies")
        sf_nodes = mesh.cells[fs[:, 0][:, None], HEX_FACES[fs[:, 1]]]
        nodes, inv = np.unique(sf_nodes, return_inverse=True)
        inv = inv.reshape(-1, 4)
        w = face_node_areas(mesh.points, sf_nodes)
        area = np.bincount(inv.ravel(), weights=w.ravel(), minlength=len(nodes))
        Xs = mesh.points[sf_nodes]
        fn = np.cross(Xs[:, 2] - Xs[:, 0], Xs[:, 3] - Xs[:, 1])  # area-weighted outward normal
        ns = np.zeros((len(nodes), 3))
        for c in range(3):
            ns[:, c] = np.bincount(inv.ravel(), weights=np.repeat(fn[:, c], 4), minlength=len(nodes))
        ns /= np.linalg.norm(ns, axis=1, keepdims=True)
        # thickness of the slave element below each face, averaged per node (area-weighted)
        opp = mesh.cells[fs[:, 0][:, None], HEX_FACES[_OPPOSITE[fs[:, 1]]]]
        h_face = np.linalg.norm(Xs.mean(1) - mesh.points[opp].mean(1), axis=1)
        h = np.bincount(inv.ravel(), weights=(w * h_face[:, None]).ravel(), minlength=len(nodes)) / area
        E = min(E_cell[fs[:, 0]].min(), E_cell[fm[:, 0]].min())
        # projection on the master faces: nearest face centres first
        mf_nodes = mesh.cells[fm[:, 0][:, None], HEX_FACES[fm[:, 1]]]
        Xm = mesh.points[mf_nodes]
        kq = min(12, len(fm))
        _, cand = cKDTree(Xm.mean(1)).query(mesh.points[nodes], k=kq)
        cand = cand.reshape(len(nodes), kq)
        xs = np.repeat(mesh.points[nodes], kq, axis=0)
        xi, eta, xp = _project(xs, Xm[cand.ravel()])
        inside = (np.abs(xi) <= 1.0 + 1e-6) & (np.abs(eta) <= 1.0 + 1e-6)
        d = np.where(inside, np.linalg.norm(xs - xp, axis=1), np.inf).reshape(len(nodes), kq)
        best = np.argmin(d, axis=1)
        sel = np.arange(len(nodes)) * kq + best
        ok = np.isfinite(d[np.arange(len(nodes)), best])
        face = cand.ravel()[sel]
        N, dxi, deta = _bilinear(xi[sel], eta[sel])
        t1 = np.einsum("pa,pai->pi", dxi, Xm[face])
        t2 = np.einsum("pa,pai->pi", deta, Xm[face])
        nm = np.cross(t1, t2)
        nm /= np.linalg.norm(nm, axis=1, keepdims=True)
        ok &= np.einsum("ij,ij->i", nm, ns) < -0.5  # the surfaces face each other
        g0 = np.einsum("ij,ij->i", mesh.points[nodes] - xp[sel], nm)
        keep = np.flatnonzero(ok)
        seed = np.zeros(len(keep), bool)
        if pair.contact_point is not None:
            dist = np.linalg.norm(mesh.points[nodes[keep]] - np.asarray(pair.contact_point), axis=1)
            seed[dist <= max(pair.contact_radius, dist.min() if len(dist) else 0.0)] = True
        elif len(keep):
            seed[g0[keep] <= g0[keep].min() + 1e-9] = True
        parts.append(dict(pair=np.full(len(keep), ip), node=nodes[keep], area=area[keep], normal=nm[keep], point=xp[sel][keep],
                          gap0=g0[keep], penalty=factor * E / h[keep], mnodes=mf_nodes[face[keep]], N=N[keep],
                          candidate=g0[keep] < pair.search_gap, seed=seed))
    cat = {k: np.concatenate([p[k] for p in parts]) if parts else np.zeros(0) for k in
           ("pair", "node", "area", "gap0", "penalty", "candidate", "seed")}
    normal = np.concatenate([p["normal"] for p in parts]) if parts else np.zeros((0, 3))
    point = np.concatenate([p["point"] for p in parts]) if parts else np.zeros((0, 3))
    mnodes = np.concatenate([p["mnodes"] for p in parts]) if parts else np.zeros((0, 4), np.int64)
    Nm = np.concatenate([p["N"] for p in parts]) if parts else np.zeros((0, 4))
    k = len(cat["node"])
    node = cat["node"].astype(np.int64)
    rows = np.concatenate([np.repeat(np.arange(k), 3), np.repeat(np.arange(k), 12)])
    cols = np.concatenate([(3 * node[:, None] + np.arange(3)).ravel(), (3 * mnodes[:, :, None] + np.arange(3)).ravel()])
    vals = np.concatenate([normal.ravel(), (-Nm[:, :, None] * normal[:, None, :]).ravel()])
    G = sp.csr_matrix((vals, (rows, cols)), shape=(k, n_dof))
    return ContactSet(cat["pair"].astype(np.int64), node, cat["area"], normal, point, cat["gap0"], cat["penalty"], G,
                      cat["candidate"].astype(bool), cat["seed"].astype(bool))


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
            raise GearfeError("contact compliance matrix is not positive definite on the active set") from None
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
            raise GearfeError(
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
            raise ConvergenceError("contact active set", "a repeated set (cycling)", viol, it)
        seen.add(key)
        A = A_new
    raise ConvergenceError("contact active set", f"{int(changed.sum())} nodes still switching", viol, max_iterations)


def penalty_active_set(W, B, H, ghat, fhat, k, area, active0, opts: ContactOptions, h_scale) -> ActiveSetSolution:
    """Active set, with the penalty raised until penetration <= tolerance, then the doubling check."""
    scale = 1.0
    sol = active_set(W, B, H, ghat, fhat, k, active0, opts.max_iterations, h_scale)
    pen = float(np.max(-sol.gap[sol.active], initial=0.0))
    raises = 0
    while pen > opts.max_penetration:
        raises += 1
        if raises > 12:
            raise ConvergenceError("penalty penetration", f"max_penetration = {opts.max_penetration} mm", pen, raises)
        scale *= max(2.0, 1.5 * pen / opts.max_penetration)
        sol = active_set(W, B, H, ghat, fhat, scale * k, sol.active, opts.max_iterations, h_scale)
        pen = float(np.max(-sol.gap[sol.active], initial=0.0))
    change = float("nan")
    if opts.penalty_check and sol.active.any():
        for _ in range(8):
            sol2 = active_set(W, B, H, ghat, fhat, 2.0 * scale * k, sol.active, opts.max_iterations, h_scale)
            p1 = float(np.max(sol.lam / area))
            p2 = float(np.max(sol2.lam / area))
            change = abs(p2 - p1) / p1
            if change < opts.penalty_check_tol:
                break
            scale, sol = 2.0 * scale, sol2
        else:
            raise ConvergenceError("penalty doubling check", f"penalty_check_tol = {opts.penalty_check_tol}", change, 8)
    return ActiveSetSolution(sol.lam, sol.u_free, sol.gap, sol.active, sol.iterations, scale, change)
