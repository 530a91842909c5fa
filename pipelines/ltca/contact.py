r"""The loaded contact of a gear pair at one position: tooth pairs within reach, their contact lines, the solve.

Gaps from the TCA (:class:`tca.planetary_mesh.MeshTE`). At driving-gear angle φ the branch k of
the pair in contact has the largest Δφ2; every other branch k' with a finite value is a pair of
teeth within reach, separated by the rotation γ_k' = Δφ2_k - Δφ2_k' ≥ 0 of the driven gear. Its
potential contact point is the reference pair's TCA point at φ - k'p1 (the pair touches there when
the driven gear is turned back by γ_k'), with the common normal n, the relative curvatures
λ1 ≤ λ2 and the major axis t of the contact ellipse (:func:`tca.ellipse.contact_ellipse`).

Contact lines. Each pair's line runs through its point along t, cut into slices of length Δs at
ξ_s; the initial separation of slice s along n is (second order in ξ)

    g_s = γ_k' |m2_s| + λ1 ξ_s² / 2,       m2_s = ((x_s - o2) × n) . a2          (moment arm, mm),

and only slices on both flanks (inside their face grids) with g_s ≤ ``reach`` are kept.

Compliance of slice s under the slice loads F [N]:

    δ_s = sum_t W_st F_t + δ_loc(w_s),   W = sum_i A_i C_i A_i^T,  w_s = F_s / Δs [N/mm],

A_i the bilinear weights of the slice points on gear i's flank grid and C_i its condensed
compliance (:mod:`pipelines.ltca.compliance`, global part), δ_loc the Hertzian flattening of both
bodies (:func:`pipelines.ltca.compliance.flattening`, constant c) with the Hertz half-width b_s = (8 w_s R (1 - ν²) / (π E))^(1/2), R = 1/λ2 (Johnson 1985,
Eq. 4.43 for two cylinders of one material).

Contact problem (linear complementarity with torque balance). The driven gear turns rigidly by
Δ [rad] against the torque T [N mm]:

    d_s = g_s + δ_s(F) - Δ |m2_s| ≥ 0,   F_s ≥ 0,   F_s d_s = 0,   sum_s F_s |m2_s| = T.

Solved by an active set (the bordered system on the active slices, dropping negative loads and
adding penetrating slices until neither happens), inside a fixed-point loop on the local
compliance δ_loc(w_s)/F_s (logarithmic in w_s), until the loads change by less than 1e-7 of the
total. Results: the elastic rotation -Δ (the driven gear lags: the loaded TE is Δφ2 - Δ), the load
of each pair of teeth, the Hertz line-contact pressure p0_s = (w_s E / (2π (1 - ν²) R))^(1/2) along
the lines, and the mesh stiffness k = ΣF / (Δ |m2_0|) [N/mm] (normal force over normal approach at
the loaded pair's point).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from tca.contact import PlacedFlank
from tca.ellipse import contact_ellipse
from tca.errors import ConvergenceError, GeometryError
from tca.pair import GearPair
from tca.planetary_mesh import MeshTE

from pipelines.ltca.compliance import flattening

__all__ = ["ContactLines", "contact_lines", "LoadedContact", "solve_contact"]


@dataclass(frozen=True, eq=False)
class ContactLines:
    """The slices of every pair of teeth within reach at one position (module docstring)."""

    phi1: float  # [rad]
    te: float  # unloaded Δφ2 [rad]
    k: int  # branch of the pair in contact
    branches: tuple  # branch k' of each pair of teeth (in order of ``pair``)
    teeth: tuple  # (driver tooth, driven tooth) of each pair, the gears' own indices
    pair: np.ndarray  # (S,) index into branches
    xi: np.ndarray  # (S,) [mm] along the contact line
    x: np.ndarray  # (S, 3) slice points, pair frame [mm]
    gap: np.ndarray  # (S,) initial separation [mm]
    arm: np.ndarray  # (S,) |m2_s| [mm]
    radius: np.ndarray  # (S,) R = 1/λ2 [mm]
    depth: np.ndarray  # (S, 2) distance to the teeth's centre planes [mm]
    ds: float  # slice length [mm]
    W: np.ndarray  # (S, S) global compliance [mm/N]
    arm0: float  # arm of the loaded pair's TCA point [mm]
    dropped: tuple  # branches within reach but outside the modelled teeth


def _interp_params(mte: MeshTE, phi_ref: float):
    """Reference-pair TCA parameters (u1, v1, u2, v2) at phi_ref by linear interpolation, or None."""
    ref = mte.result.reference
    t = (phi_ref - ref.phi1[0]) / mte.h
    n = len(ref.phi1)
    i0 = int(math.floor(t + 1e-9))
    w = t - i0
    if not 0 <= i0 < n:
        return None
    x0 = ref.x[i0, :4]
    if abs(w) < 1e-9:
        return x0 if np.all(np.isfinite(x0)) else None
    if i0 + 1 >= n:
        return None
    x1 = ref.x[i0 + 1, :4]
    if not (np.all(np.isfinite(x0)) and np.all(np.isfinite(x1))):
        return None
    return (1 - w) * x0 + w * x1


def _rotz(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def contact_lines(pair: GearPair, mte: MeshTE, phi: float, flanks: tuple, ds: float, reach: float) -> ContactLines:
    """Slices of the pairs of teeth within ``reach`` [mm] at driver angle ``phi`` [rad] (module docstring)."""
    fc1, fc2 = flanks
    val, ks = mte.branches(np.array([phi], float))
    val = val[0]
    q = int(np.argmax(val))
    te, k = float(val[q]), int(ks[q])
    if not math.isfinite(te):
        raise GeometryError(f"{pair.gear1.name}-{pair.gear2.name}", "no contact", f"at phi = {math.degrees(phi):.6f} deg")
    m1, m2 = pair.mounts()
    f1, f2 = PlacedFlank(pair.gear1, pair.side1, m1), PlacedFlank(pair.gear2, pair.side2, m2)
    p1, p2 = 2 * math.pi / pair.gear1.teeth, 2 * math.pi / pair.gear2.teeth
    N1, N2 = pair.gear1.teeth, pair.gear2.teeth
    B = max(pair.gear1.face_width, pair.gear2.face_width)
    rows = []
    branches, teeth, dropped = [], [], []
    arm0 = float("nan")
    order = sorted(range(len(ks)), key=lambda i: (ks[i] != k, abs(ks[i] - k)))  # the loaded pair first
    for i in order:
        kk = int(ks[i])
        if not math.isfinite(val[i]):
            continue
        gam = te - float(val[i])
        phr = phi - kk * p1
        par = _interp_params(mte, phr)
        if par is None:
            continue
        ph2 = pair.ratio * phr + float(val[i])  # the pair's own touching angle of the driven gear
        w1, _, _ = f1.world(np.array([par[0]]), np.array([par[1]]), np.array([phr]))
        w2, _, _ = f2.world(np.array([par[2]]), np.array([par[3]]), np.array([ph2]))
        _, _, ang, lam = contact_ellipse(w1, w2, 1.0, m1.axis[None, :])
        x0, n = w1.r[0], w1.n[0]
        a1 = m1.axis
        e1 = a1 - (a1 @ n) * n
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(n, e1)
        t = math.cos(ang[0]) * e1 + math.sin(ang[0]) * e2
        l1, l2 = float(lam[0, 0]), float(lam[0, 1])
        if not l2 > 0:
            continue
        arm_c = abs(float(np.cross(x0 - m2.origin, n) @ m2.axis))
        if gam * arm_c > reach:
            continue
        d = kk - k  # model teeth: world tooth -kk is model tooth k - kk
        j1, j2 = (-d) % N1, (-d) % N2
        if j1 not in fc1.teeth or j2 not in fc2.teeth:
            dropped.append(kk)
            continue
        L = min(B, math.sqrt(2 * max(reach - gam * arm_c, 0.0) / l1) if l1 > 0 else B)
        ns = int(math.ceil(L / ds))
        xi = ds * np.arange(-ns, ns + 1)
        xs = x0[None, :] + xi[:, None] * t[None, :]
        arm = np.abs(np.einsum("ij,j->i", np.cross(xs - m2.origin, n), m2.axis))
        g = gam * arm + 0.5 * max(l1, 0.0) * xi**2
        # slice points in each model's gear frame, on the model tooth of this pair
        R1, _ = m1.rotation(phr)
        R2, _ = m2.rotation(ph2)
        xg1 = (xs - m1.origin) @ R1 @ _rotz(-d * p1).T
        xg2 = (xs - m2.origin) @ R2 @ _rotz(-d * p2).T
        loc1, loc2 = fc1.locate(xg1), fc2.locate(xg2)
        ok = loc1.inside & loc2.inside & (g <= reach)
        if not ok.any():
            continue
        if kk == k:
            arm0 = arm_c
        idx = len(branches)
        branches.append(kk)
        teeth.append((int((-kk) % N1), int((-kk) % N2)))
        rows.append((idx, xi[ok], xs[ok], g[ok], arm[ok], np.full(ok.sum(), 1.0 / l2),
                     np.stack([loc1.depth[ok], loc2.depth[ok]], 1), loc1, loc2, ok))
    if not rows or branches[0] != k:
        raise GeometryError(f"{pair.gear1.name}-{pair.gear2.name}", "contact line",
                            f"the loaded pair at phi = {math.degrees(phi):.6f} deg is not on the modelled flanks")
    cat = lambda j: np.concatenate([r[j] for r in rows])  # noqa: E731
    pidx = np.concatenate([np.full(len(r[1]), r[0]) for r in rows])
    A1 = _stack([r[7] for r in rows], [r[9] for r in rows], len(fc1.points))
    A2 = _stack([r[8] for r in rows], [r[9] for r in rows], len(fc2.points))
    W = _project(A1, fc1.C) + _project(A2, fc2.C)
    W = 0.5 * (W + W.T)
    return ContactLines(float(phi), te, k, tuple(branches), tuple(teeth), pidx, cat(1), cat(2), cat(3), cat(4), cat(5),
                        cat(6), float(ds), W, arm0, tuple(dropped))


def _stack(locs, oks, m):
    """Sparse weights (S, m) of the kept slices of all pairs over one gear's flank nodes."""
    return sp.vstack([loc.matrix(m)[ok] for loc, ok in zip(locs, oks)], format="csr")


def _project(A, C) -> np.ndarray:
    """A C A^T for sparse A (S, m) and dense C (m, m), on the columns A touches."""
    cols = np.unique(A.indices)
    Ac = A[:, cols].toarray()
    return Ac @ C[np.ix_(cols, cols)] @ Ac.T


@dataclass(frozen=True)
class LoadedContact:
    """Solution of one position and torque: loads [N], rotation [rad], pressures [MPa], iterations."""

    F: np.ndarray  # (S,) slice loads [N]
    delta: float  # rigid rotation of the driven gear closing the gaps [rad] (> 0)
    pressure: np.ndarray  # (S,) Hertz line-contact peak pressure p0 [MPa]
    pair_force: np.ndarray  # (pairs,) [N]
    stiffness: float  # mesh stiffness [N/mm]
    iterations: int
    fixed_point: int


def _local(F, lines: ContactLines, E: float, nu: float, c: float, w_guess: float) -> np.ndarray:
    """Local compliance δ_loc(w_s) / F_s [mm/N] at the current loads (w_guess where F_s = 0)."""
    w = np.where(F > 0, F / lines.ds, w_guess)
    Es = E / (2.0 * (1.0 - nu**2))
    b = np.sqrt(4.0 * w * lines.radius / (math.pi * Es))
    d = flattening(w, b, lines.depth[:, 0], E, nu, c) + flattening(w, b, lines.depth[:, 1], E, nu, c)
    return d / (w * lines.ds)


def _active_set(M, g, a, T, A0, maxit=200):
    """LCP with torque balance on dense M (module docstring): loads, rotation, iterations."""
    A = A0.copy()
    seen = set()
    for it in range(1, maxit + 1):
        idx = np.flatnonzero(A)
        n = len(idx)
        K = np.zeros((n + 1, n + 1))
        K[:n, :n] = M[np.ix_(idx, idx)]
        K[:n, n] = -a[idx]
        K[n, :n] = a[idx]
        rhs = np.concatenate([-g[idx], [T]])
        sol = np.linalg.solve(K, rhs)
        F = np.zeros(len(g))
        F[idx] = sol[:n]
        delta = sol[n]
        if (F[idx] < 0).any():
            A[idx[F[idx] < 0]] = False
            if not A.any():
                A[idx[np.argmax(F[idx])]] = True
            continue
        d = g + M @ F - a * delta
        viol = (~A) & (d < -1e-12 * max(1.0, abs(delta) * a.max()))
        if not viol.any():
            return F, float(delta), it
        key = (A.tobytes(), viol.tobytes())
        if key in seen:
            raise ConvergenceError("ltca active set", "a repeated set (cycling)", float(-d[viol].min()), it)
        seen.add(key)
        A |= viol
    raise ConvergenceError("ltca active set", "active set still changing", float("nan"), maxit)


def solve_contact(lines: ContactLines, torque: float, E: float, nu: float, c: float, tol: float = 1e-7,
                  maxit: int = 30) -> LoadedContact:
    """Loads, elastic rotation, pressures and mesh stiffness at torque [N mm]; c the flattening constant (module docstring)."""
    a = lines.arm
    L0 = max(float(np.ptp(lines.xi[lines.pair == 0])), lines.ds)
    w_guess = torque / lines.arm0 / L0
    F = np.zeros(len(a))
    A = lines.gap <= lines.gap.min() + 1e-12
    its = 0
    for fp in range(1, maxit + 1):
        M = lines.W + np.diag(_local(F, lines, E, nu, c, w_guess))
        F_new, delta, it = _active_set(M, lines.gap, a, torque, A)
        its += it
        change = float(np.abs(F_new - F).max())
        F = F_new
        A = F > 0
        if change <= tol * F.sum():
            break
    else:
        raise ConvergenceError("ltca local compliance", "fixed point on the Hertzian flattening", change / F.sum(), maxit)
    w = F / lines.ds
    p0 = np.sqrt(w * E / (2 * math.pi * (1 - nu**2) * lines.radius))
    pf = np.bincount(lines.pair, weights=F, minlength=len(lines.branches))
    k = float(F.sum() / (delta * lines.arm0)) if delta > 0 else float("inf")
    return LoadedContact(F, delta, p0, pf, k, its, fp)
