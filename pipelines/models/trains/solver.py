r"""The loaded contact of a whole train at one position: every mesh's slices and the rigid bodies, one problem.

Unknowns. Slice loads :math:`F_s \ge 0` [N] of every mesh m (the slices of the pair LTCA,
:func:`pipelines.models.ltca.contact.contact_lines`) and the small rigid motions q of the free bodies
(rotations [rad] about their axes, translations [mm]): each planet's rotation (a twin planet is one
body of two members), the sun's rotation (the torque T acts on it), the sun's translations where it
floats or sits on a support of finite stiffness, the planets' translations where their pins are
elastic. The ring is held; the carrier frame is the frame of the problem.

Gaps (Eq. T1). For slice s of a mesh whose driver A pushes the driven body B along the unit normal
:math:`\mathbf n_s` (out of A's tooth) at :math:`\mathbf x_s`, a rigid motion of body X (rotation
:math:`\omega_X` about the unit axis :math:`\mathbf a_X` through :math:`\mathbf o_X`, translation
:math:`\mathbf t_X`) moves the point by :math:`\omega_X\mathbf a_X\times(\mathbf x_s-\mathbf o_X)+\mathbf t_X`,
and the approach of the flanks is

.. math::
    (\mathbf B q)_s = \mathbf n_s\cdot(\mathbf u_A - \mathbf u_B),\qquad
    B_{s,\omega_X} = \pm((\mathbf x_s-\mathbf o_X)\times\mathbf n_s)\cdot\mathbf a_X,\quad
    B_{s,\mathbf t_X} = \pm\mathbf n_s

(+ for the driver, − for the driven body), so that

.. math::
    d = c + M F - B q \ge 0,\qquad F \ge 0,\qquad F_s d_s = 0          \qquad (T1)

with c the separations at q = 0 (:mod:`pipelines.models.trains.model`) and
:math:`M = \mathrm{diag}_m(W_m + \mathrm{diag}\,\delta_{loc}/F)` block-diagonal per mesh (each mesh's
flank compliance, :mod:`pipelines.models.ltca.compliance`; bodies shared by several meshes are not
coupled through their bodies).

Equilibrium (virtual work) of every free rigid DOF, with K the stiffnesses of pins and supports and
f the external loads (the sun torque T on its rotation):

.. math:: B^T F + K q = f.                                                              \qquad (T2)

Solution. (T1)–(T2) are the optimality conditions of the convex minimisation

.. math::
    \min_q\ \Phi(q) = \tfrac12 F(q)^T M F(q) + \tfrac12 q^T K q - f^T q,\qquad
    \nabla\Phi = B^T F(q) + K q - f,                                                    \qquad (T3)

where F(q) solves, mesh by mesh, the linear complementarity problem (T1) at fixed q (M_m symmetric
positive definite: a unique solution, found by block principal pivoting with Murty's least-index rule
as the fallback, :func:`mesh_lcp`). Φ is convex and continuously differentiable, piecewise quadratic
with Hessian :math:`H = K + \sum_m B_{A}^T M_{AA}^{-1} B_{A}` on the meshes' active sets A. Newton's method with a
Levenberg–Marquardt shift (a body that touches nothing, a planet touching on one side only, has
flat directions) and a backtracking line search on Φ converges to the exact solution of the
piecewise quadratic in a finite number of steps once the active sets settle. A planet without
contact has a flat Φ along its rotation: its load is zero and its angle anywhere in its backlash.

The local (Hertzian) part of M depends on the loads (:func:`pipelines.models.ltca.contact.local_compliance`):
a fixed point on it, as in the pair LTCA, until the loads change by less than ``tol`` of the total.

For one mesh with the driven rotation as the only DOF this is the pair LTCA's problem
(:func:`pipelines.models.ltca.contact.solve_contact`): a test checks that both give the same loads.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg.lapack import dpotrf, dpotrs

from fem.material import Material
from tca.errors import ConvergenceError

from pipelines.models.ltca.compliance import flattening
from pipelines.models.ltca.contact import SliceLaw

__all__ = ["MeshBlock", "RigidSystem", "SolveOptions", "TrainSolution", "Warm", "mesh_lcp", "solve_train"]


@dataclass(frozen=True, eq=False)
class MeshBlock:
    """One mesh at one position: its slices' global compliance, separations at q = 0, rigid rows and Hertz law."""

    W: np.ndarray  # (S, S) [mm/N]
    c: np.ndarray  # (S,) [mm]
    B: np.ndarray  # (S, nq) rigid rows (Eq. T1)
    law: SliceLaw  # lengths, radii, depths of the slices (local compliance)
    kappa: np.ndarray  # (S,) p0/b of the slices [MPa/mm] (pressure)
    w_guess: float  # line load [N/mm] for the local compliance of an unloaded slice


@dataclass(frozen=True, eq=False)
class RigidSystem:
    """Stiffness K (nq, nq) [N/mm, N mm/rad], loads f (nq,) [N, N mm], residual scales (nq,) of the rigid DOFs."""

    K: np.ndarray
    f: np.ndarray
    scale: np.ndarray


@dataclass(frozen=True)
class SolveOptions:
    """Tolerances: loads (fixed point, relative to the total), equilibrium (relative to ``scale``), iterations."""

    tol: float = 1e-7
    eq_tol: float = 1e-10
    max_fixed_point: int = 40
    max_newton: int = 80
    tangent: bool = True  # Newton (True) or secant (False) iteration on the local compliance


@dataclass(frozen=True, eq=False)
class Warm:
    """A starting point: rigid motions q and the loads of each mesh (the local compliances start from them)."""

    q: np.ndarray
    F: tuple


@dataclass(frozen=True, eq=False)
class TrainSolution:
    """Loads F per mesh [N], rigid motions q, pressures per mesh [MPa], iterations."""

    F: tuple
    q: np.ndarray
    pressure: tuple
    newton: int
    fixed_point: int
    lcp: int

    def warm(self) -> Warm:
        return Warm(self.q, self.F)


def mesh_lcp(M: np.ndarray, c: np.ndarray, A0: np.ndarray | None = None, maxit: int = 500, solve=None):
    """F >= 0 with d = c + M F >= 0, F d = 0 for symmetric positive definite M (S, S); returns (F, active, iterations).

    Block principal pivoting from the active set ``A0`` (default: the slices with c <= 0): solve on the active set,
    drop slices with negative loads and add penetrating ones, all at once; when the number of infeasible slices
    has not decreased for three steps, Murty's least-index rule (one slice at a time: finite for P-matrices).
    ``solve(idx, rhs)``: M[idx, idx]^-1 rhs (default: a dense solve; the train solve passes cached factors).
    """
    S = len(c)
    if S == 0:
        return np.zeros(0), np.zeros(0, bool), 0
    A = (c <= 0) if A0 is None else A0.copy()
    scale = max(float(np.abs(c).max()), 1e-30)
    best, stall, murty = S + 1, 0, False
    F = np.zeros(S)
    for it in range(1, maxit + 1):
        F[:] = 0.0
        idx = np.flatnonzero(A)
        if len(idx):
            F[idx] = np.linalg.solve(M[np.ix_(idx, idx)], -c[idx]) if solve is None else solve(idx, -c[idx])
        d = c + M @ F
        bad_f = A & (F < 0)
        bad_d = ~A & (d < -1e-13 * scale)
        nbad = int(bad_f.sum() + bad_d.sum())
        if nbad == 0:
            F[~A] = 0.0
            return F, A, it
        if nbad < best:
            best, stall = nbad, 0
        else:
            stall += 1
            murty = murty or stall >= 3
        if murty:
            j = int(np.flatnonzero(bad_f | bad_d)[0])
            A[j] = not A[j]
        else:
            A = (A & ~bad_f) | bad_d
    raise ConvergenceError("train LTCA: mesh contact (LCP)", "active set still changing", float(nbad), maxit)


class _Meshes:
    """The blocks at the current local compliances: evaluates F(q), Φ(q) and the Hessian (module docstring)."""

    def __init__(self, blocks, rigid: RigidSystem, diag, shift=None):
        self.blocks, self.rigid = blocks, rigid
        self.M = [b.W + np.diag(dg) for b, dg in zip(blocks, diag)]
        self.c = [b.c if shift is None else b.c + sh for b, sh in zip(blocks, shift or [None] * len(blocks))]
        self.active = [None] * len(blocks)
        self.touch = [None] * len(blocks)
        self.lcp = 0
        self.factors = [dict() for _ in blocks]  # Cholesky factors of M[A, A] per active set (M is fixed here)

    def solve(self, j: int, idx, rhs):
        """M_j[idx, idx]^-1 rhs with the Cholesky factor of that active set computed once (LAPACK potrf/potrs called
        directly: the solves are small and many, scipy's checking wrappers cost more than the arithmetic)."""
        key = idx.tobytes()
        f = self.factors[j].get(key)
        if f is None:
            f, info = dpotrf(self.M[j][np.ix_(idx, idx)], lower=0, clean=0)
            if info != 0:
                raise ConvergenceError("train LTCA: mesh contact", f"compliance block not positive definite "
                                       f"(potrf info {info})", float(info), 0)
            self.factors[j][key] = f
        x, info = dpotrs(f, rhs, lower=0)
        return x

    def loads(self, q):
        F = []
        for j, (b, M, c) in enumerate(zip(self.blocks, self.M, self.c)):
            cq = c - b.B @ q
            Fj, Aj, it = mesh_lcp(M, cq, self.active[j], solve=lambda idx, rhs, j=j: self.solve(j, idx, rhs))
            self.lcp += it
            F.append(Fj)
            self.active[j] = Aj
            d = cq + M @ Fj
            self.touch[j] = Aj | (d <= 1e-12 * max(float(np.abs(cq).max()), 1e-30))
        return F

    def phi(self, q, F) -> float:
        e = sum(0.5 * float(Fj @ (M @ Fj)) for Fj, M in zip(F, self.M))
        return e + 0.5 * float(q @ (self.rigid.K @ q)) - float(self.rigid.f @ q)

    def gradient(self, q, F) -> np.ndarray:
        g = self.rigid.K @ q - self.rigid.f
        for b, Fj in zip(self.blocks, F):
            g = g + b.B.T @ Fj
        return g

    def hessian(self) -> np.ndarray:
        H = self.rigid.K.copy()
        for j, (b, A) in enumerate(zip(self.blocks, self.touch)):  # the touching slices: the curvature on closing
            idx = np.flatnonzero(A)
            if len(idx):
                BA = b.B[idx]
                H += BA.T @ self.solve(j, idx, BA)
        return H


def _newton(mesh: _Meshes, q0: np.ndarray, opts: SolveOptions):
    """Minimise Φ (Eq. T3) from q0 at fixed local compliances: (q, F, iterations).

    A DOF without curvature (nothing it moves touches) but with a load on it is first moved to the nearest
    contact along its load; otherwise a Newton step on the scaled Hessian, with an exact line search (the root of
    the monotone, piecewise linear derivative of Φ along the step, by the Illinois method): a Newton step can be
    far too long where the Hessian misses slices that are about to close, or unbounded along a flat direction
    (a planet rolling on the sun without touching the ring)."""
    q = q0.copy()
    F = mesh.loads(q)
    scale = mesh.rigid.scale
    nq = len(q)
    for it in range(1, opts.max_newton + 1):
        g = mesh.gradient(q, F)
        big = np.abs(g) > opts.eq_tol * scale
        if not big.any():
            return q, F, it
        H = mesh.hessian()
        dH = np.diag(H).copy()
        flat = dH <= 1e-12 * max(float(dH.max()), 1e-300)
        push = flat & big
        if push.any():
            q = q + _first_contact(mesh, q, F, -np.where(push, g, 0.0))
            F = mesh.loads(q)
            continue
        sq = np.sqrt(np.where(flat, 1.0, dH))
        A = H / np.outer(sq, sq) + 1e-12 * np.eye(nq)
        A[flat, :] = 0.0
        A[:, flat] = 0.0
        A[flat, flat] = 1.0
        step = np.linalg.solve(A, np.where(flat, 0.0, -g / sq)) / sq
        slope = float(g @ step)
        if not slope < 0:
            step = -np.where(flat, 0.0, g / dH.clip(1e-300))  # the diagonal step: a descent direction
            slope = float(g @ step)
        q, F = _line_search(mesh, q, step, slope)
    g = mesh.gradient(q, F)
    raise ConvergenceError("train LTCA: equilibrium of the rigid bodies (Newton)", "not converged",
                           float(np.max(np.abs(g) / scale)), opts.max_newton)


def _line_search(mesh: _Meshes, q, step, slope: float, maxit: int = 60):
    """(q + t step, loads) with t the minimiser of Φ along the step (t = 1 when Φ still decreases there)."""
    qn = q + step
    Fn = mesh.loads(qn)
    d_hi = float(mesh.gradient(qn, Fn) @ step)
    if d_hi <= 0:
        return qn, Fn
    t_lo, d_lo, t_hi = 0.0, slope, 1.0
    side = 0
    for _ in range(maxit):
        t = t_hi - d_hi * (t_hi - t_lo) / (d_hi - d_lo)
        if not t_lo < t < t_hi:
            t = 0.5 * (t_lo + t_hi)
        qn = q + t * step
        Fn = mesh.loads(qn)
        d = float(mesh.gradient(qn, Fn) @ step)
        if abs(d) <= 1e-3 * abs(slope) or (t_hi - t_lo) <= 1e-14 * t_hi:
            return qn, Fn
        if d < 0:
            t_lo, d_lo = t, d
            if side == -1:
                d_hi *= 0.5
            side = -1
        else:
            t_hi, d_hi = t, d
            if side == 1:
                d_lo *= 0.5
            side = 1
    return qn, Fn


def _closing(mesh: _Meshes, q, F, step) -> float:
    """Fraction t of ``step`` at which the first open slice closes (inf: none)."""
    t_min = math.inf
    for b, M, c, Fj in zip(mesh.blocks, mesh.M, mesh.c, F):
        rate = b.B @ step
        d = c - b.B @ q + M @ Fj
        ok = (rate > 0) & (d > 0)
        if ok.any():
            t_min = min(t_min, float(np.min(d[ok] / rate[ok])))
    return t_min


def _first_contact(mesh: _Meshes, q, F, direction) -> np.ndarray:
    """A step along ``direction`` (nq,) to just beyond the first slice it closes (1.01 times that distance)."""
    t = _closing(mesh, q, F, direction)
    if not math.isfinite(t):
        raise ConvergenceError("train LTCA: a body under load touches nothing", "no slice closes along the load",
                               float(np.linalg.norm(direction)), 0)
    return (1.01 * t) * direction


def _local_law(blocks, F, material: Material, c_loc: float, tangent: bool):
    """The local (Hertzian) compliance of every mesh at loads F: (diagonal, shift of c) per mesh. Secant: δ_s/F_s, no
    shift. Tangent (loaded slices): δ_s(F) ≈ δ_s(F0) + D_s (F − F0), D_s = dδ_s/dF_s, so M gets D and c gets
    δ_s(F0) − D_s F0: Newton's method on the flattening law (the converged loads are the same).

    D_s in closed form: each body's flattening d_k = a w (ln(2 h_k / b) + c), a = 2(1 − ν²)/(π E), with
    b ∝ √w (:func:`pipelines.models.ltca.compliance.flattening`), has dd_k/dw = d_k/w − a/2 where d_k > 0 (0 where it
    is clipped at 0); with w = F/ℓ, D_s = δ_s/F_s − a n_s/(2 ℓ_s), n_s the bodies with d_k > 0."""
    diag, shift = [], []
    a = 2.0 * (1.0 - material.nu ** 2) / (math.pi * material.E)
    Es = material.E / (2.0 * (1.0 - material.nu ** 2))
    for b, Fj in zip(blocks, F):
        law = b.law
        w = np.where(Fj > 0, Fj / law.length, b.w_guess)
        hb = np.sqrt(4.0 * w * law.radius / (math.pi * Es))
        d0 = flattening(w, hb, law.depth[:, 0], material, c_loc)
        d1 = flattening(w, hb, law.depth[:, 1], material, c_loc)
        sec = (d0 + d1) / (w * law.length)  # = local_compliance(Fj, law, material, c_loc, b.w_guess)
        on = Fj > 0
        if not tangent or not on.any():
            diag.append(sec)
            shift.append(np.zeros_like(sec))
            continue
        D = np.where(on, sec - 0.5 * a * ((d0 > 0).astype(float) + (d1 > 0)) / law.length, sec)
        diag.append(D)
        shift.append(np.where(on, (sec - D) * Fj, 0.0))
    return diag, shift


def solve_train(blocks, rigid: RigidSystem, material: Material, c_loc: float, warm: Warm | None = None,
                opts: SolveOptions = SolveOptions()) -> TrainSolution:
    """Loads, rigid motions and pressures of the train at one position and load (module docstring)."""
    nq = len(rigid.f)
    q = np.zeros(nq) if warm is None else np.asarray(warm.q, float).copy()
    F = [np.zeros(len(b.c)) for b in blocks] if warm is None else [np.asarray(x, float) for x in warm.F]
    if warm is not None and any(len(x) != len(b.c) for x, b in zip(F, blocks)):
        F = [np.zeros(len(b.c)) for b in blocks]
    its = lcps = 0
    for fp in range(1, opts.max_fixed_point + 1):
        diag, shift = _local_law(blocks, F, material, c_loc, opts.tangent)
        mesh = _Meshes(blocks, rigid, diag, shift)
        mesh.active = [(Fj > 0) if Fj.any() else None for Fj in F]
        q, F_new, it = _newton(mesh, q, opts)
        its += it
        lcps += mesh.lcp
        total = max(sum(float(x.sum()) for x in F_new), 1e-300)
        change = max((float(np.abs(a - b).max()) if len(a) else 0.0) for a, b in zip(F_new, F))
        F = F_new
        if change <= opts.tol * total:
            break
    else:
        raise ConvergenceError("train LTCA: local compliance", "fixed point on the Hertzian flattening",
                               change / total, opts.max_fixed_point)
    p = [np.sqrt(2.0 * b.kappa * Fj / b.law.length / math.pi) for b, Fj in zip(blocks, F)]
    return TrainSolution(tuple(F), q, tuple(p), its, fp, lcps)
