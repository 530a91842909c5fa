r"""Contact of two placed tooth flanks: tangency (Eqs. 1.7–1.9), edge and corner contact.

Surface-to-surface tangency, unknowns :math:`x=(u_1,v_1,u_2,v_2,\phi_2)` for given
:math:`\phi_1` — five scalar equations equivalent to Eqs. (1.7)–(1.8), written as in (3.18):

.. math::
    r_f^{(1)} - r_f^{(2)} = 0,\qquad n_f^{(1)}\cdot r^{(2)}_{f,u} = 0,\qquad n_f^{(1)}\cdot r^{(2)}_{f,v} = 0 .

The Jacobian is analytic (surfaces provide second derivatives). When the point of tangency
lies outside a working area, the bounded surfaces touch along a boundary instead (edge
contact): the boundary curve :math:`c(u_i,v_i)=0` of surface *i* is tangent to surface *j*,

.. math::
    r_f^{(1)} - r_f^{(2)} = 0,\qquad c(u_i, v_i) = 0,\qquad
    n_f^{(j)} \cdot (c_v\, r^{(i)}_{f,u} - c_u\, r^{(i)}_{f,v}) = 0,

or at a corner of the working area (two boundaries), where the three position equations
alone fix :math:`(u_j, v_j, \phi_2)`. Residuals are in mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from tca.geometry.gear import Gear
from tca.geometry.surfaces import SurfacePoints, ToothSurface, cross3
from tca.numerics.transforms import Mount

__all__ = ["PlacedFlank", "tangency_system", "edge_system", "edge_edge_system", "corner_system", "boundary_derivs",
           "corner_params", "foot_points", "area_margin"]


@dataclass(frozen=True, eq=False)
class PlacedFlank:
    """A flank (gear, side) of tooth `tooth` mounted in S_f."""

    gear: Gear
    side: int
    mount: Mount
    tooth: int = 0

    @property
    def surface(self) -> ToothSurface:
        return self.gear.surface(self.side)

    def frame(self, phi):
        """R, dR/dphi (n,3,3) and t, dt/dphi (n,3) mapping the tooth surface to S_f."""
        Rm, dRm = self.mount.rotation(phi)
        if self.tooth == 0 and self.gear.runout == 0.0:
            return Rm, dRm, np.broadcast_to(self.mount.origin, np.shape(phi) + (3,)), np.zeros(np.shape(phi) + (3,))
        Rk, tk = self.gear.tooth_transform(np.full(np.shape(phi), self.tooth))
        R = Rm @ Rk
        dR = dRm @ Rk
        t = self.mount.origin + np.einsum("...ij,...j->...i", Rm, tk)
        dt = np.einsum("...ij,...j->...i", dRm, tk)
        return R, dR, t, dt

    def world(self, u, v, phi):
        """Surface points in S_f, plus the local points and the frame."""
        loc = self.surface.evaluate(u, v)
        R, dR, t, dt = self.frame(phi)
        return loc.transformed(R, t), loc, (R, dR, t, dt)

    def constraints(self, loc: SurfacePoints, u) -> np.ndarray:
        """Working-area constraints (..., 4) of local points: fillet, tip, z_max, z_min (<= 0 inside)."""
        return self.gear.constraints(self.side, loc, u)


def _dot(a, b):
    return np.einsum("...i,...i", a, b)


def _rot(R, a):
    return np.einsum("...ij,...j->...i", R, a)


def _dn(loc: SurfacePoints, which: str):
    """Derivative of the local unit normal w.r.t. u or v."""
    c = cross3(loc.r_u, loc.r_v)
    nc = np.linalg.norm(c, axis=-1, keepdims=True)
    if which == "u":
        dc = cross3(loc.r_uu, loc.r_v) + cross3(loc.r_u, loc.r_uv)
    else:
        dc = cross3(loc.r_uv, loc.r_v) + cross3(loc.r_u, loc.r_vv)
    n = loc.n
    return (dc - _dot(dc, n)[..., None] * n) / nc * np.sign(_dot(c, n))[..., None]


def tangency_system(f1: PlacedFlank, f2: PlacedFlank, phi1: np.ndarray):
    """fun(x, idx) -> (F, J) for Newton; x = (u1, v1, u2, v2, phi2), phi1 given per member."""

    def fun(x, idx):
        u1, v1, u2, v2, p2 = x.T
        w1, l1, (R1, _, _, _) = f1.world(u1, v1, phi1[idx])
        w2, l2, (R2, dR2, t2, dt2) = f2.world(u2, v2, p2)
        n1 = w1.n
        F = np.concatenate([w1.r - w2.r, _dot(n1, w2.r_u)[:, None], _dot(n1, w2.r_v)[:, None]], -1)
        dn1u = _rot(R1, _dn(l1, "u"))
        dn1v = _rot(R1, _dn(l1, "v"))
        dp2 = _rot(dR2, l2.r) + dt2
        J = np.zeros(x.shape[:-1] + (5, 5))
        J[:, :3, 0] = w1.r_u
        J[:, :3, 1] = w1.r_v
        J[:, :3, 2] = -w2.r_u
        J[:, :3, 3] = -w2.r_v
        J[:, :3, 4] = -dp2
        J[:, 3, 0] = _dot(dn1u, w2.r_u)
        J[:, 3, 1] = _dot(dn1v, w2.r_u)
        J[:, 3, 2] = _dot(n1, w2.r_uu)
        J[:, 3, 3] = _dot(n1, w2.r_uv)
        J[:, 3, 4] = _dot(n1, _rot(dR2, l2.r_u))
        J[:, 4, 0] = _dot(dn1u, w2.r_v)
        J[:, 4, 1] = _dot(dn1v, w2.r_v)
        J[:, 4, 2] = _dot(n1, w2.r_uv)
        J[:, 4, 3] = _dot(n1, w2.r_vv)
        J[:, 4, 4] = _dot(n1, _rot(dR2, l2.r_v))
        return F, J

    return fun


def boundary_derivs(flank: PlacedFlank, loc: SurfacePoints, u, which: int):
    """Value, d/du and d/dv of working-area constraint `which` (0 fillet, 1 tip, 2 z_max, 3 z_min), of the
    ridge of an end relief (4 at the z_max end, 5 at the z_min end) or of the kink of a tip relief (6: the
    rack parameter u_s where the relief starts, positive on the relieved side; :mod:`tca.pair.relief`)."""
    g = flank.gear
    if which == 6:
        return u - g.rack.relief_start, np.ones_like(u), np.zeros_like(u)
    ar = g.area(flank.side)
    if which == 0:
        return ar.u_form - u, -np.ones_like(u), np.zeros_like(u)
    if which == 1:
        rho = np.hypot(loc.r[..., 0], loc.r[..., 1])
        cu = g.kappa * (loc.r[..., 0] * loc.r_u[..., 0] + loc.r[..., 1] * loc.r_u[..., 1]) / rho
        cv = g.kappa * (loc.r[..., 0] * loc.r_v[..., 0] + loc.r[..., 1] * loc.r_v[..., 1]) / rho
        return g.kappa * (rho - ar.r_tip), cu, cv
    if which == 2:
        return loc.r[..., 2] - ar.z_max, loc.r_u[..., 2], loc.r_v[..., 2]
    if which in (4, 5):
        top, bot = g.end_relief.starts(g.face_width)
        zs = top if which == 4 else bot
        return loc.r[..., 2] - zs, loc.r_u[..., 2], loc.r_v[..., 2]
    return ar.z_min - loc.r[..., 2], -loc.r_u[..., 2], -loc.r_v[..., 2]


def _fd_jacobian(res, x, idx, h):
    """Central-difference Jacobian, all perturbations evaluated in one batched call."""
    m = x.shape[-1]
    k = len(x)
    E = np.eye(m) * h
    xs = np.concatenate([x] + [x + E[j] for j in range(m)] + [x - E[j] for j in range(m)])
    R = res(xs, np.tile(idx, 2 * m + 1))
    F = R[:k]
    Rp = R[k:(m + 1) * k].reshape(m, k, -1)
    Rm = R[(m + 1) * k:].reshape(m, k, -1)
    J = np.moveaxis((Rp - Rm) / (2 * h[:, None, None]), 0, -1)
    return F, J


_H = np.array([1e-6, 1e-6, 1e-6, 1e-6, 1e-8])


def edge_system(f1: PlacedFlank, f2: PlacedFlank, phi1, edge_on: int, which: int):
    """fun(x, idx) for the boundary `which` of flank `edge_on` (1 or 2) tangent to the other flank."""

    def res(x, idx):
        u1, v1, u2, v2, p2 = x.T
        w1, l1, (R1, _, _, _) = f1.world(u1, v1, phi1[idx])
        w2, l2, (R2, _, _, _) = f2.world(u2, v2, p2)
        if edge_on == 1:
            c, cu, cv = boundary_derivs(f1, l1, u1, which)
            T = cv[:, None] * w1.r_u - cu[:, None] * w1.r_v
            tang = _dot(w2.n, T)
        else:
            c, cu, cv = boundary_derivs(f2, l2, u2, which)
            T = cv[:, None] * w2.r_u - cu[:, None] * w2.r_v
            tang = _dot(w1.n, T)
        return np.concatenate([w1.r - w2.r, c[:, None], tang[:, None]], -1)

    return lambda x, idx: _fd_jacobian(res, x, idx, _H)


def edge_edge_system(f1: PlacedFlank, f2: PlacedFlank, phi1, b1: int, b2: int):
    """fun(x, idx): boundary b1 of flank 1 crossing boundary b2 of flank 2 (edge-to-edge contact).

    Unknowns x = (u1, v1, u2, v2, phi2); equations r_f1 = r_f2, c1_b1 = 0, c2_b2 = 0 (analytic Jacobian).
    """

    def fun(x, idx):
        u1, v1, u2, v2, p2 = x.T
        w1, l1, _ = f1.world(u1, v1, phi1[idx])
        w2, l2, (_, dR2, _, dt2) = f2.world(u2, v2, p2)
        c1, c1u, c1v = boundary_derivs(f1, l1, u1, b1)
        c2, c2u, c2v = boundary_derivs(f2, l2, u2, b2)
        F = np.concatenate([w1.r - w2.r, c1[:, None], c2[:, None]], -1)
        J = np.zeros(x.shape[:-1] + (5, 5))
        J[:, :3, 0], J[:, :3, 1] = w1.r_u, w1.r_v
        J[:, :3, 2], J[:, :3, 3] = -w2.r_u, -w2.r_v
        J[:, :3, 4] = -(_rot(dR2, l2.r) + dt2)
        J[:, 3, 0], J[:, 3, 1] = c1u, c1v
        J[:, 4, 2], J[:, 4, 3] = c2u, c2v
        return F, J

    return fun


def corner_params(flank: PlacedFlank, a: int, b: int, u0: float, v0: float):
    """(u, v) of the corner where working-area boundaries a and b of a flank meet."""
    x = np.array([u0, v0], float)
    for _ in range(50):
        loc = flank.surface.evaluate(x[0], x[1])
        ca = boundary_derivs(flank, loc, x[0], a)
        cb = boundary_derivs(flank, loc, x[0], b)
        F = np.array([ca[0], cb[0]], float)
        J = np.array([[ca[1], ca[2]], [cb[1], cb[2]]], float)
        dx = np.linalg.solve(J, -F)
        x += dx
        if np.abs(dx).max() < 1e-14:
            break
    return x


def corner_system(f1: PlacedFlank, f2: PlacedFlank, phi1, corner_on: int, uv: np.ndarray):
    """fun(x, idx) for fixed points uv (n, 2) or (2,) of flank `corner_on` lying on the other flank.

    Unknowns x = (u_other, v_other, phi2): three position equations (analytic Jacobian). Used for
    corner contact and to put a boundary point of one flank on the other.
    """
    uv = np.asarray(uv, float)

    def fun(x, idx):
        uo, vo, p2 = x.T
        pts = uv[idx] if uv.ndim == 2 else np.broadcast_to(uv, (len(idx), 2))
        uc, vc = pts[:, 0], pts[:, 1]
        J = np.empty(x.shape[:-1] + (3, 3))
        if corner_on == 1:
            w1, _, _ = f1.world(uc, vc, phi1[idx])
            w2, l2, (_, dR2, _, dt2) = f2.world(uo, vo, p2)
            J[:, :, 0], J[:, :, 1] = -w2.r_u, -w2.r_v
        else:
            w1, _, _ = f1.world(uo, vo, phi1[idx])
            w2, l2, (_, dR2, _, dt2) = f2.world(uc, vc, p2)
            J[:, :, 0], J[:, :, 1] = w1.r_u, w1.r_v
        J[:, :, 2] = -(_rot(dR2, l2.r) + dt2)
        return w1.r - w2.r, J

    return fun


def foot_points(f: PlacedFlank, uv0, phi: float, x: np.ndarray, tol: float = 1e-10, maxit: int = 12):
    """Foot points on flank f (at angle phi) of points x (S, 3), from (u, v) = uv0 mapped over the tangent
    plane, by Newton's method on the squared distance: (SurfacePoints, converged mask, (u, v) (S, 2)).
    Within reach of the flank a point converges in a few steps; one that has not in ``maxit`` lies far
    from it (typically past the flank's extension) and is left out."""
    S = len(x)
    w0, _, _ = f.world(np.array([uv0[0]]), np.array([uv0[1]]), np.array([phi]))
    J0 = np.stack([w0.r_u[0], w0.r_v[0]], 1)
    duv = np.linalg.lstsq(J0, (x - w0.r[0]).T, rcond=None)[0]
    u, v = uv0[0] + duv[0], uv0[1] + duv[1]
    ph = np.full(S, float(phi))
    ok = np.zeros(S, bool)  # converged
    dot = lambda a, b: np.einsum("ij,ij->i", a, b)  # noqa: E731
    act = np.arange(S)
    for _ in range(maxit):  # Newton on |x - r(u, v)|^2 / 2 (second derivatives of the surface), unconverged points
        with np.errstate(invalid="ignore", divide="ignore"):  # a point run off the surface: non-finite, handled below
            w, _, _ = f.world(u[act], v[act], ph[act])
        d = x[act] - w.r
        a11 = dot(w.r_u, w.r_u) - dot(d, w.r_uu)
        a12 = dot(w.r_u, w.r_v) - dot(d, w.r_uv)
        a22 = dot(w.r_v, w.r_v) - dot(d, w.r_vv)
        b1, b2 = dot(d, w.r_u), dot(d, w.r_v)
        det = a11 * a22 - a12 * a12
        with np.errstate(all="ignore"):
            du, dv = (a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det
        bad = ~(np.isfinite(du) & np.isfinite(dv))
        du, dv = np.where(bad, 0.0, du), np.where(bad, 0.0, dv)
        u[act], v[act] = u[act] + du, v[act] + dv
        done = (np.abs(du) + np.abs(dv) < tol) & ~bad
        ok[act[done]] = True
        act = act[~done & ~bad]
        if not len(act):
            break
    with np.errstate(invalid="ignore", divide="ignore"):
        w, _, _ = f.world(u, v, ph)
    return w, ok & np.all(np.isfinite(w.r), axis=1), np.stack([u, v], 1)


def area_margin(f: PlacedFlank, uv: np.ndarray) -> np.ndarray:
    """Largest working-area constraint (fillet, tip, face ends; :meth:`tca.geometry.gear.Gear.constraints`) [mm] of
    points (u, v) (S, 2) of flank f: <= 0 inside."""
    with np.errstate(invalid="ignore", divide="ignore"):  # points off the surface: non-finite, outside
        loc = f.surface.evaluate(uv[:, 0], uv[:, 1])
        c = f.constraints(loc, uv[:, 0]).max(axis=-1)
    return np.where(np.isfinite(c), c, np.inf)
