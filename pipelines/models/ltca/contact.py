r"""The loaded contact of a gear pair at one position: tooth pairs within reach, their contact lines, the solve.

Gaps from the TCA (:class:`tca.planetary.subgear.MeshTE`). At driving-gear angle φ the branch k of
the pair in contact has the largest Δφ2; every other branch k' with a finite value is a pair of
teeth within reach, separated by the rotation γ_k' = Δφ2_k - Δφ2_k' ≥ 0 of the driven gear. Its
potential contact point is the reference pair's TCA point at φ - k'p1 (the pair touches there when
the driven gear is turned back by γ_k'), with the common normal n, the relative curvatures
λ1 ≤ λ2 and the major axis t of the contact ellipse (:func:`tca.contact.ellipse.contact_ellipse`).

Contact lines. Each pair's line runs through its point along t, cut into slices of length Δs at
ξ_s; the initial separation of slice s along n is (second order in ξ)

    g_s = γ_k' |m2_s| + λ1 ξ_s² / 2,       m2_s = ((x_s - o2) × n) . a2          (moment arm, mm),

and only slices on both flanks (inside their face grids) with g_s ≤ ``reach`` are kept.

Modelled teeth. Pair k' lies on model tooth -(k' - k) of each gear's condensed model, which is
centred on the pair in contact; a pair with slices outside the model is listed in ``dropped``.
:func:`teeth_in_reach` counts the teeth a model needs so that there is none: with ε_α + ε_β > 2 a
pair two pitches from the pair in contact can touch (three teeth are not enough).

Compliance of slice s under the slice loads F [N]:

    δ_s = sum_t W_st F_t + δ_loc(w_s),   W = sum_i A_i C_i A_i^T,  w_s = F_s / Δs [N/mm],

A_i the bilinear weights of the slice points on gear i's flank grid and C_i its condensed
compliance (:mod:`pipelines.models.ltca.compliance`, global part), δ_loc the Hertzian flattening of both
bodies (:func:`pipelines.models.ltca.compliance.flattening`, constant c) with the Hertz half-width b_s = (8 w_s R_s (1 - ν²) / (π E))^(1/2), R_s = 1/λ2 (Johnson 1985,
Eq. 4.43 for two cylinders of one material).

Curvatures of a slice. λ1 ≤ λ2 are those of the slice's own two points (:func:`_curvatures`), not the
pair's TCA point's: a helical contact line crosses the whole profile, and across it λ2 =
cos β_b (1/ρ1 + 1/ρ2) (ρ_i the transverse roll lengths) grows from the pinion's tip to its root (by a
factor 2.3 along the lines of ltca_helical_crowned.toml; with the value of a TCA point at the pinion's tip the
slice pressures there were up to 34 % low).

Contact problem (linear complementarity with torque balance). The driven gear turns rigidly by
Δ [rad] against the torque T [N mm]:

    d_s = g_s + δ_s(F) - Δ |m2_s| ≥ 0,   F_s ≥ 0,   F_s d_s = 0,   sum_s F_s |m2_s| = T.

Solved by an active set (the bordered system on the active slices, dropping negative loads and
adding penetrating slices until neither happens), inside a fixed-point loop on the local
compliance δ_loc(w_s)/F_s (logarithmic in w_s), until the loads change by less than 1e-7 of the
total. Results: the elastic rotation -Δ (the driven gear lags: the loaded TE is Δφ2 - Δ), the load
of each pair of teeth, the pressure along the lines, and the mesh stiffness k = ΣF / (Δ |m2_0|)
[N/mm] (normal force over normal approach at the loaded pair's point).

Pressure of a slice. In Hertz's elliptical contact (semi-axes a along the line, b across it) the
load per unit length of the line is w(ξ) = (π/2) p(ξ) b(ξ) with p(ξ) = p0 (1 - ξ²/a²)^(1/2) and
b(ξ) = b (1 - ξ²/a²)^(1/2), so p/b = p0/b =: κ along the whole line, a constant of the curvatures
and the material alone (p0 and b both grow as P^(1/3)), and

    p_s = (2 κ_s w_s / π)^(1/2),    κ_s = p0 / b of the Hertz ellipse of the slice's curvatures
                                    (:func:`hertz_kappa`, Johnson 1985, Eqs. 4.39–4.40),

which is exact for a Hertzian load distribution and becomes the line-contact value
(w E* / (π R))^(1/2), κ = E* λ2 / 2, when λ1 → 0. (The line-contact value alone, which ignores the
curvature λ1 along the line, is 7 % below the elliptical Hertz peak on the crowned pair.)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import scipy.sparse as sp

from fem.material import Material
from tca.contact.systems import PlacedFlank, area_margin, foot_points
from tca.contact.ellipse import contact_ellipse
from tca.errors import ConvergenceError, GeometryError
from tca.pair.gear_pair import GearPair
from tca.pair.bounded import boundary_curve
from tca.pair.result import ContactKind
from tca.planetary.subgear import MeshTE
from tca.pair.te import mesh_contact, tied_branches

from pipelines.models.ltca.compliance import flattening
from pipelines.models.stress.sizing import hertz_contact

__all__ = ["Meshing", "ContactLines", "PairSlices", "pair_slices", "loaded_branch", "contact_lines", "teeth_in_reach",
           "separation", "edge_slices", "hertz_kappa", "LoadedContact", "solve_contact"]


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
    kappa: np.ndarray  # (S,) p0/b of the Hertz ellipse of the slice's curvatures [MPa/mm] (module docstring)
    depth: np.ndarray  # (S, 2) distance to the teeth's centre planes [mm]
    ds: float  # slice length [mm] (nominal)
    W: np.ndarray  # (S, S) global compliance [mm/N]
    arm0: float  # arm of the loaded pair's TCA point [mm]
    dropped: tuple  # branches within reach but outside the modelled teeth
    length: np.ndarray  # (S,) slice lengths [mm]
    edge: np.ndarray  # (S,) boundary of an edge slice: 10 flank + boundary (1 tip, 2 z_max, 3 z_min); 0 on a line


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


class PairSlices(NamedTuple):
    """The slices of one pair of teeth within reach (pair frame), before they are put on the flank grids."""

    kk: int  # branch of the pair
    d: int  # offset from the pair in contact, kk - k: world tooth -kk is model tooth -d
    phr: float  # reference-pair driver angle phi - kk p1 [rad]
    ph2c: float  # driven-gear angle where the loaded pair touches [rad]
    arm_c: float  # |m2| at the pair's TCA point [mm]
    l1: float  # relative curvatures λ1 <= λ2 [1/mm]
    l2: float
    xi: np.ndarray  # (S,) along the line or boundary [mm]
    xs: np.ndarray  # (S, 3) gear-1 points
    xs2: np.ndarray  # (S, 3) gear-2 points
    n: np.ndarray  # (S, 3) unit normal out of gear 1's tooth
    gap: np.ndarray  # (S,) exact separation [mm]
    touching: np.ndarray  # (S,) on both working areas and within reach
    length: np.ndarray  # (S,) [mm]
    edge: np.ndarray  # (S,) boundary code (0 on a line)
    lam: np.ndarray  # (S, 2) relative curvatures λ1 <= λ2 of each slice's two points [1/mm]


def loaded_branch(pair: GearPair, mte: MeshTE, phi: float) -> tuple[int, float, np.ndarray, np.ndarray]:
    """The branch in contact at driver angle ``phi`` [rad] (ties of conjugate flanks resolved as everywhere,
    :func:`tca.pair.te.mesh_contact`), its Δφ2 [rad], and the values and indices of all branches."""
    val, ks = mte.branches(np.array([phi], float))
    val = val[0]
    te = float(val.max())
    if not math.isfinite(te):
        raise GeometryError(f"{pair.gear1.name}-{pair.gear2.name}", "no contact", f"at phi = {math.degrees(phi):.6f} deg")
    tied = tied_branches(pair, val).sum() > 1
    k = mesh_contact(mte.result, float(phi)).k if tied else int(ks[int(np.argmax(val))])
    return k, te, val, ks


def pair_slices(pair: GearPair, mte: MeshTE, phi: float, ds: float, reach: float, offsets=None, loaded=None):
    """The pairs of teeth within ``reach`` [mm] at driver angle ``phi`` [rad] that have slices (module docstring),
    the pair in contact first, as :class:`PairSlices`; ``offsets``: a predicate on the offset d from the pair in
    contact (the pairs it rejects are not cut); ``loaded``: :func:`loaded_branch` at phi if known."""
    k, te, val, ks = loaded if loaded is not None else loaded_branch(pair, mte, phi)
    m1, m2 = pair.mounts()
    f1, f2 = PlacedFlank(pair.gear1, pair.side1, m1), PlacedFlank(pair.gear2, pair.side2, m2)
    p1 = 2 * math.pi / pair.gear1.teeth
    B = max(pair.gear1.face_width, pair.gear2.face_width)
    order = sorted(range(len(ks)), key=lambda i: (ks[i] != k, abs(ks[i] - k)))  # the loaded pair first
    for i in order:
        kk = int(ks[i])
        if not math.isfinite(val[i]) or (offsets is not None and not offsets(kk - k)):
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
        ph2c = pair.ratio * phr + te  # the driven gear where the loaded pair touches
        kind = _ref_kind(mte, phr)
        parts = []
        L = min(B, math.sqrt(2 * max(reach - gam * arm_c, 0.0) / l1) if l1 > 0 else B)
        line = _line_slices(Meshing(f1, f2, phr, ph2c, par, gam * arm_c), x0, t, L, ds)
        if line is not None:  # the TCA point on both working areas: the line through it
            parts.append(line)
        if kind != ContactKind.SURFACE:  # an edge contact, or a tangency beyond a boundary: the boundaries too
            eg = edge_slices(f1, f2, par, phr, ph2c, ds)
            if len(eg[0]) and line is not None:  # not where the line already is
                dist = np.linalg.norm(eg[1][:, None, :] - line[1][None, :, :], axis=2).min(axis=1)
                eg = tuple(a_[dist > ds] for a_ in eg)
            if len(eg[0]):
                parts.append(eg)
        if not parts:
            continue
        xi, xs, xs2, n_s, g, conv, seg, edge, lam = (np.concatenate([q[j] for q in parts]) for j in range(9))
        bad = ~(np.isfinite(lam).all(1) & (lam[:, 1] > 0))  # the pair's curvatures where a slice's are not convex
        lam[bad] = (l1, l2)
        yield PairSlices(kk, kk - k, phr, ph2c, arm_c, l1, l2, xi, xs, xs2, n_s, g, conv & (g <= reach), seg, edge, lam)


def contact_lines(pair: GearPair, mte: MeshTE, phi: float, flanks: tuple, ds: float, reach: float,
                  material: Material) -> ContactLines:
    """Slices of the pairs of teeth within ``reach`` [mm] at driver angle ``phi`` [rad] (module docstring);
    the ``material`` (E [MPa], ν) for the pressure law of the slices. Pairs with slices outside the modelled teeth are
    listed in ``dropped`` (:func:`teeth_in_reach` sizes the model so that there are none)."""
    fc1, fc2 = flanks
    m1, m2 = pair.mounts()
    p1, p2 = 2 * math.pi / pair.gear1.teeth, 2 * math.pi / pair.gear2.teeth
    N1, N2 = pair.gear1.teeth, pair.gear2.teeth
    rows = []
    branches, teeth, dropped = [], [], []
    arm0 = float("nan")
    loaded = loaded_branch(pair, mte, phi)
    k, te = loaded[0], loaded[1]
    for q in pair_slices(pair, mte, phi, ds, reach, loaded=loaded):
        kk, d = q.kk, q.d
        if (-d) % N1 not in fc1.teeth or (-d) % N2 not in fc2.teeth:  # world tooth -kk is model tooth -d
            if q.touching.any():
                dropped.append(kk)
            continue
        arm = np.abs(np.einsum("ij,ij->i", np.cross(q.xs - m2.origin, q.n), np.broadcast_to(m2.axis, q.xs.shape)))
        # slice points in each model's gear frame, on the model tooth of this pair
        R1, _ = m1.rotation(q.phr)
        R2, _ = m2.rotation(q.ph2c)
        xg1 = (q.xs - m1.origin) @ R1 @ _rotz(-d * p1).T
        xg2 = (q.xs2 - m2.origin) @ R2 @ _rotz(-d * p2).T
        # on the working areas (``touching``, exact); the flank grids' faces for the compliance (the faceted grid
        # approximates the boundary curves: a face within EDGE_SLACK of a face size)
        loc1, loc2 = fc1.locate(xg1, EDGE_SLACK), fc2.locate(xg2, EDGE_SLACK)
        ok = q.touching & loc1.inside & loc2.inside
        if not ok.any():
            continue
        if d == 0:
            arm0 = q.arm_c if not q.edge.any() else float(arm[ok][np.argmin(q.gap[ok])])
        idx = len(branches)
        branches.append(kk)
        teeth.append((int((-kk) % N1), int((-kk) % N2)))
        lam = q.lam[ok]
        rows.append((idx, q.xi[ok], q.xs[ok], q.gap[ok], arm[ok], 1.0 / lam[:, 1],
                     np.stack([loc1.depth[ok], loc2.depth[ok]], 1), loc1, loc2, ok,
                     np.array([hertz_kappa(a, b, material) for a, b in lam]), q.length[ok], q.edge[ok]))
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
                        cat(10), cat(6), float(ds), W, arm0, tuple(dropped), cat(11), cat(12))


def teeth_in_reach(pair: GearPair, mte: MeshTE, phis, ds: float, reach: float, teeth: int = 1) -> int:
    """Teeth per gear that a model centred on the pair in contact needs to hold every pair of teeth with slices
    within ``reach`` [mm] (:func:`pair_slices`) at the driver angles ``phis`` [rad]: 2 max|d| + 1, at least
    ``teeth`` (the pairs inside that model are not cut again).

    With ε_α + ε_β > 2 a third pair may touch on either side of the pair in contact: the crowned helical pair of
    ltca_helical_crowned.toml (ε_γ = 2.7) has, at φ1 = -10.565°, a pair two pitches away 1.6 µm from contact,
    which a three-tooth model left out.
    """
    half = (teeth - 1) // 2
    for phi in np.asarray(phis, float):
        for q in pair_slices(pair, mte, float(phi), ds, reach, offsets=lambda d: abs(d) > half):
            if q.touching.any():
                half = max(half, abs(q.d))
    return 2 * half + 1


def hertz_kappa(l1: float, l2: float, material: Material) -> float:
    """p0 / b [MPa/mm] of the Hertz ellipse of relative curvatures λ1 <= λ2 [1/mm] (independent of the load);
    E* λ2 / 2 for a line contact (λ1 <= 0)."""
    line = material.E / (2.0 * (1.0 - material.nu**2)) * l2 / 2.0
    if not l1 > 0:
        return line
    hz = hertz_contact((l1, l2), 1.0, material, 1e12)
    return line if hz.line else hz.p0 / hz.b


def _ref_kind(mte: MeshTE, phi_ref: float) -> int:
    """Contact kind of the reference pair at the grid node nearest phi_ref."""
    ref = mte.result.reference
    i = int(round((phi_ref - ref.phi1[0]) / mte.h))
    return int(ref.kind[min(max(i, 0), len(ref.kind) - 1)])


BOUNDARY_TOL = 1e-6  # [mm] a point this close to a boundary lies on it (an edge contact of the TCA)
EDGE_SLACK = 0.25  # fraction of a grid face beyond the border within which a boundary point is on its flank grid


@dataclass(frozen=True, eq=False)
class Meshing:
    """Two placed flanks at the angles where a pair of teeth touches, and where its solves start:
    ``par`` (u1, v1, u2, v2) [mm] a point near the contact, ``gap0`` [mm] a starting separation."""

    f1: PlacedFlank
    f2: PlacedFlank
    phi1: float  # [rad]
    phi2: float  # [rad]
    par: np.ndarray
    gap0: float = 0.0


def in_area(f: PlacedFlank, uv: np.ndarray, tol: float = BOUNDARY_TOL) -> np.ndarray:
    """Points (u, v) (S, 2) [mm] of flank f inside its working area (within ``tol`` [mm] of it)."""
    return area_margin(f, uv) <= tol


def _line_slices(m: Meshing, x0, t, L: float, ds: float):
    """Slices of the line through the reference point x0 along t [mm], inside both working areas and
    within L of x0, cut into equal slices of about ds ending on the area boundaries (:func:`_clip`);
    None when x0 is not on both working areas. Same tuple as :func:`edge_slices` (edge code 0)."""
    ns = int(math.ceil(L / ds)) + 1
    xi = ds * np.arange(-ns, ns + 1)
    *_, conv, margin = separation(m, x0[None, :] + xi[:, None] * t[None, :], with_margin=True)
    if not (conv[ns] and margin[ns] <= BOUNDARY_TOL):
        return None
    lo, hi = _clip(xi, margin, conv, ns, ds)
    n_sl = max(1, int(math.ceil((hi - lo) / ds - 1e-9)))
    seg_len = (hi - lo) / n_sl
    xi = lo + seg_len * (np.arange(n_sl) + 0.5)
    xl = x0[None, :] + xi[:, None] * t[None, :]
    xs, n_s, xs2, g, conv, lam = separation(m, xl, with_curvature=True)
    xs, xs2 = np.where(conv[:, None], xs, xl), np.where(conv[:, None], xs2, xl)
    return xi, xs, xs2, n_s, g, conv, np.full(len(xi), seg_len), np.zeros(len(xi), int), lam


def _clip(xi: np.ndarray, margin: np.ndarray, conv: np.ndarray, i0: int, ds: float) -> tuple[float, float]:
    """Ends [mm] of the run of a line's points inside both working areas around index i0: where the area
    margin crosses zero (linear interpolation between the last point inside and the first outside), or
    half a slice beyond the last point where the line ends inside."""
    inside = conv & (margin <= BOUNDARY_TOL)
    ends = []
    for step in (-1, 1):
        i = i0
        while 0 <= i + step < len(xi) and inside[i + step]:
            i += step
        j = i + step
        if 0 <= j < len(xi) and np.isfinite(margin[j]) and margin[j] > margin[i]:
            ends.append(xi[i] + (xi[j] - xi[i]) * (-margin[i]) / (margin[j] - margin[i]))
        else:
            ends.append(xi[i] + step * 0.5 * ds)
    return ends[0], ends[1]


_PIECES: dict = {}


def _boundary_pieces(f: PlacedFlank, b: int, ds: float):
    """Midpoints (arc length [mm], (u, v) (n, 2)) and length [mm] of the n pieces of boundary b of flank f
    (in the tooth's own frame: the same at every angle; cached per gear, side, boundary and ds)."""
    key = (id(f.gear), f.side, b, ds)
    hit = _PIECES.get(key)
    if hit is not None and hit[0] is f.gear:
        return hit[1]
    (t0, t1), tmap = boundary_curve(f, b)
    ts = np.linspace(t0, t1, 401)
    uvb = tmap(ts)
    r = f.surface.evaluate(uvb[:, 0], uvb[:, 1]).r
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(r, axis=0), axis=1))])
    n = max(1, int(round(s[-1] / ds)))
    sm = (np.arange(n) + 0.5) * s[-1] / n
    out = (sm, tmap(np.interp(sm, s, ts)), float(s[-1] / n))
    _PIECES[key] = (f.gear, out)
    return out


def edge_slices(f1: PlacedFlank, f2: PlacedFlank, par, phi1: float, phi2: float, ds: float):
    """Slices along the boundaries (tip, face ends) of both flanks, for a pair whose reference point
    ``par`` (u1, v1, u2, v2) [mm] is an edge contact or a tangency of the extended surfaces outside a
    working area: such a pair can touch only along a boundary (beyond a flank's form circle, along the
    mating tip). Callers keep the pieces within reach and on both working areas.

    Each boundary curve (:func:`tca.pair.bounded.boundary_curve`) at the flanks' angles phi1, phi2
    [rad] is cut into pieces of arc length about ``ds`` [mm]; the separation of a piece's midpoint
    is its distance from the other flank along that flank's normal (:func:`tca.contact.systems.foot_points`).
    Returns xi (arc length along the boundary from its start: z_min for a tip, the form circle for a face
    end), gear-1 and gear-2 points (S, 3), the unit
    normal out of gear 1's tooth, separations [mm], converged mask, piece lengths [mm], the
    boundary code 10 flank + boundary and the relative curvatures (S, 2) of the extended surfaces there.
    """
    out = []
    sides = ((1, f1, f2, phi1, phi2, par[0:2], par[2:4]), (2, f2, f1, phi2, phi1, par[2:4], par[0:2]))
    for which, f, g, ph_f, ph_g, uv, uvg in sides:
        for b in (1, 2, 3):
            sm, uvm, piece = _boundary_pieces(f, b, ds)
            n = len(sm)
            we, _, _ = f.world(uvm[:, 0], uvm[:, 1], np.full(n, ph_f))
            wg, ok, uvf = foot_points(g, uvg, ph_g, we.r)
            ok &= in_area(g, uvf)  # the foot point on the other flank's working area
            gap = np.einsum("ij,ij->i", we.r - wg.r, wg.n)
            if which == 1:
                x1, x2, nrm, lam = we.r, wg.r, -wg.n, _curvatures(we, wg, f1, ok)
            else:
                x1, x2, nrm, lam = wg.r, we.r, wg.n, _curvatures(wg, we, f1, ok)
            out.append((sm, x1, x2, nrm, gap, ok, np.full(n, piece), np.full(n, 10 * which + b), lam))
    if not out:
        e = np.zeros((0, 3))
        return np.zeros(0), e, e, e, np.zeros(0), np.zeros(0, bool), np.zeros(0), np.zeros(0, int), np.zeros((0, 2))
    return tuple(np.concatenate([o[j] for o in out]) for j in range(9))


def separation(m: Meshing, x, tol: float = 1e-10, maxit: int = 30, with_margin: bool = False,
               with_curvature: bool = False):
    """Exact separation of two flanks along gear 1's normal at the points of gear 1's flank nearest x (S, 3).

    Gear 1's flank ``m.f1`` at angle ``m.phi1``, gear 2's at ``m.phi2`` [rad]; ``m.par`` (u1, v1, u2, v2) [mm] a
    point near the line (start of the iterations), ``m.gap0`` [mm] a starting separation. Foot points P1 on flank 1
    (:func:`tca.contact.systems.foot_points`), then the normal line P1 + s n1 meets flank 2
    at P2 (Newton on r2(u2, v2) - P1 - s n1 = 0): s is the separation [mm] (> 0 apart). Returns P1,
    n1, P2, s and the mask of points where both solves converged with both points inside their flanks'
    working areas (:func:`in_area`); ``with_margin``: also the larger of the two :func:`area_margin`;
    ``with_curvature``: also the relative curvatures λ1 <= λ2 (S, 2) [1/mm] of the two points (:func:`_curvatures`).
    """
    f1, f2, par, phi1, phi2, gap0 = m.f1, m.f2, m.par, m.phi1, m.phi2, m.gap0
    S = len(x)
    w1, ok1, uv1 = foot_points(f1, par[:2], phi1, x, tol, maxit)
    u, v = uv1[:, 0], uv1[:, 1]
    P1, n1 = w1.r, w1.n
    u2 = np.full(S, float(par[2]))
    v2 = np.full(S, float(par[3]))
    sg = np.full(S, float(gap0))
    ph2 = np.full(S, float(phi2))
    # start: the foot points' offsets from the line's centre mapped onto flank 2's tangent plane
    w2, _, _ = f2.world(u2[:1], v2[:1], ph2[:1])
    J0 = np.stack([w2.r_u[0], w2.r_v[0]], 1)
    duv = np.linalg.lstsq(J0, (P1 - P1[len(P1) // 2]).T, rcond=None)[0] if S > 1 else np.zeros((2, S))
    u2, v2 = u2 + duv[0] - duv[0][S // 2], v2 + duv[1] - duv[1][S // 2]
    ok2 = np.zeros(S, bool)
    for _ in range(maxit):
        w2, _, _ = f2.world(u2, v2, ph2)
        res = w2.r - P1 - sg[:, None] * n1
        J = np.stack([w2.r_u, w2.r_v, -n1], 2)  # (S, 3, 3)
        with np.errstate(all="ignore"):
            step = np.linalg.solve(J, -res[..., None])[..., 0]
        step = np.where(np.isfinite(step), step, 0.0)
        u2, v2, sg = u2 + step[:, 0], v2 + step[:, 1], sg + step[:, 2]
        ok2 = np.abs(step).sum(1) < tol
        if ok2.all():
            break
    w2, _, _ = f2.world(u2, v2, ph2)
    margin = np.maximum(area_margin(f1, np.stack([u, v], 1)), area_margin(f2, np.stack([u2, v2], 1)))
    ok = ok1 & ok2 & np.isfinite(sg) & (margin <= BOUNDARY_TOL)
    if with_margin:
        return P1, n1, w2.r, sg, ok, margin
    if with_curvature:
        return P1, n1, w2.r, sg, ok, _curvatures(w1, w2, f1, ok)
    return P1, n1, w2.r, sg, ok


def _curvatures(w1, w2, f1: PlacedFlank, ok: np.ndarray) -> np.ndarray:
    """Relative curvatures λ1 <= λ2 (S, 2) [1/mm] of gear 1's points w1 and gear 2's points w2 (world), as at the
    TCA point (:func:`tca.ellipse.contact_ellipse`); NaN outside ``ok`` (points that did not converge on a flank)."""
    lam = np.full((len(ok), 2), np.nan)
    ok = ok & np.all([np.isfinite(a).all(axis=1) for a in (*w1, *w2)], axis=0)
    if ok.any():
        sub = lambda w: type(w)(*(a[ok] for a in w))  # noqa: E731
        lam[ok] = contact_ellipse(sub(w1), sub(w2), 1.0, np.broadcast_to(f1.mount.axis, (int(ok.sum()), 3)))[3]
    return lam


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
    pressure: np.ndarray  # (S,) peak pressure of each slice (2 κ w / π)^(1/2) [MPa]
    pair_force: np.ndarray  # (pairs,) [N]
    stiffness: float  # mesh stiffness [N/mm]
    iterations: int
    fixed_point: int


def _local(F, lines: ContactLines, material: Material, c: float, w_guess: float) -> np.ndarray:
    """Local compliance δ_loc(w_s) / F_s [mm/N] at the current loads (w_guess where F_s = 0)."""
    w = np.where(F > 0, F / lines.length, w_guess)
    Es = material.E / (2.0 * (1.0 - material.nu**2))
    b = np.sqrt(4.0 * w * lines.radius / (math.pi * Es))
    d = flattening(w, b, lines.depth[:, 0], material, c) + flattening(w, b, lines.depth[:, 1], material, c)
    return d / (w * lines.length)


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


def solve_contact(lines: ContactLines, torque: float, material: Material, c: float, tol: float = 1e-7,
                  maxit: int = 30) -> LoadedContact:
    """Loads, elastic rotation, pressures and mesh stiffness at torque [N mm]; c the flattening constant (module docstring)."""
    a = lines.arm
    L0 = max(float(np.ptp(lines.xi[lines.pair == 0])), lines.ds)
    w_guess = torque / lines.arm0 / L0
    F = np.zeros(len(a))
    A = lines.gap <= lines.gap.min() + 1e-12
    its = 0
    for fp in range(1, maxit + 1):
        M = lines.W + np.diag(_local(F, lines, material, c, w_guess))
        F_new, delta, it = _active_set(M, lines.gap, a, torque, A)
        its += it
        change = float(np.abs(F_new - F).max())
        F = F_new
        A = F > 0
        if change <= tol * F.sum():
            break
    else:
        raise ConvergenceError("ltca local compliance", "fixed point on the Hertzian flattening", change / F.sum(), maxit)
    w = F / lines.length
    p0 = np.sqrt(2.0 * lines.kappa * w / math.pi)
    pf = np.bincount(lines.pair, weights=F, minlength=len(lines.branches))
    k = float(F.sum() / (delta * lines.arm0)) if delta > 0 else float("inf")
    return LoadedContact(F, delta, p0, pf, k, its, fp)
