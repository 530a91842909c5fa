r"""Tooth body of one gear tooth divided into six subvolumes (report section 1.6, Steps 1–3, Fig. 1.6).

Step 1 — the designed body (Fig. 1.6(a)). In the gear frame, at every axial level z the transverse
section of the reference tooth is bounded by its exact tooth surfaces (both sides: flank from the
start of the fillet to the tip circle, fillet, root up to the middle of the tooth space), the tip
circle :math:`r_a` (top land), the radial lines through the two space centres and the rim circle
:math:`r_i = r_f - \kappa h_{rim}` (:math:`\kappa = +1` external, :math:`-1` internal: the rim of a
ring lies outside its root circle). Surfaces are evaluated at their parameters (u, v = z), so every
boundary node lies exactly on a tooth surface.

Step 2 — auxiliary intermediate surfaces (Fig. 1.6(b)): the *mid-surface* of the tooth (in the
rim at the angle :math:`\theta_c(z)` halfway between the two space centres; above the root halfway
between the two flanks at the start of the fillets and at the tip, since crowned teeth twist a
little relative to their root), the *base* surface joining the start of the fillet on each side to
the mid-surface at the same radius (point :math:`Q_1`), and the
*split* surface from the space centre :math:`Q_3` on the root circle down to the point
:math:`M` on the mid-surface at depth :math:`d_M = \min(r_f \sin(\pi/N),\ 0.6\,h_{rim})` below the
root (a 45° cut when the rim is deep enough). They cut the body into six logical hexahedra, three
on each side of the mid-surface:

* A± — tooth above the base surface (flank, top land, mid-surface, base);
* B± — fillet region (fillet and root, base, split surface, mid-surface);
* C± — rim (split surface, space-centre line, rim circle, mid-surface).

Step 3 — nodes (Fig. 1.6(c)): each block is filled by transfinite interpolation (:mod:`mesher.tfi`)
in polar coordinates (r, θ − θ_c) at every z, between node rows placed on its four bounding
curves by the element distributions of a :class:`ToothPlan`. The rows across a half tooth (the base
surface and the split surface, from the mid-surface out to the flank and to the space centre) both
take the plan's ``half`` fractions, graded toward the surface: the element layers normal to the
fillet and root are as thin along the whole fillet as at its start. Because the bounding faces
z = ±B/2 are planes and all lateral surfaces are parameterized by z, the 3D transfinite
interpolation of each subvolume reduces to this 2D interpolation per axial level.

Conformity between neighbouring teeth: the space-centre line of the left side of a tooth is the
right one of the same tooth turned by :math:`-2\pi/N`, so tooth k+1 (turned by :math:`2\pi/N`)
meets tooth k on identical node rows.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tca.errors import ConvergenceError, GeometryError, InputError
from tca.geometry.gear import Gear

from mesher.region import fillet_start
from mesher.tfi import tfi

__all__ = ["ToothGeometry", "ToothPlan", "BLOCKS"]

BLOCKS = ("A+", "A-", "B+", "B-", "C+", "C-")
SIDES = (1, -1)
_TABLE = 257  # samples of the arclength tables


def _rot(q):
    c, s = math.cos(q), math.sin(q)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _arclength(p: np.ndarray) -> np.ndarray:
    seg = np.linalg.norm(np.diff(p, axis=-2), axis=-1)
    return np.concatenate([np.zeros(seg.shape[:-1] + (1,)), np.cumsum(seg, axis=-1)], axis=-1)


@dataclass(frozen=True, eq=False)
class ToothPlan:
    """Element counts and parameter values of the node rows on one tooth's exact boundaries.

    ``flank_u[s]`` are the flank parameters [mm] at the level ``z_ref`` from the start of the fillet
    to the tip (scaled at other levels to the local tip), ``fillet_w[s]`` the fillet angles [rad]
    from the flank down to the root, ``root_u[s]`` the root parameters [mm] from the fillet to the
    space centre; ``half[s]`` the fractions across the half tooth (mid-surface -> flank) on the base
    and top land.
    """

    flank_u: dict
    fillet_w: dict
    root_u: dict
    half: dict
    z_ref: float
    u_tip_ref: dict
    label: str = "tooth"

    def __post_init__(self):
        nA = {s: len(self.flank_u[s]) - 1 for s in SIDES}
        nB = {s: len(self.fillet_w[s]) + len(self.root_u[s]) - 2 for s in SIDES}
        if nA[1] != nA[-1] or nB[1] != nB[-1]:
            raise InputError("tooth plan", (nA, nB), "equal profile and fillet counts on both sides (shared mid-surface)")
        if min(nA[1], len(self.fillet_w[1]) - 1) < 1:
            raise InputError("tooth plan", nA, ">= 1 element on flank and fillet")

    @property
    def n_flank(self) -> int:
        return len(self.flank_u[1]) - 1

    @property
    def n_fillet_root(self) -> int:
        return len(self.fillet_w[1]) + len(self.root_u[1]) - 2

    def n_fillet(self, side: int) -> int:
        return len(self.fillet_w[side]) - 1

    def n_half(self, side: int) -> int:
        return len(self.half[side]) - 1

    def shape(self, block: str, n_rim: int) -> tuple[int, int]:
        """(n_i, n_j) elements of a block."""
        side = 1 if block[1] == "+" else -1
        ni = {"A": self.n_flank, "B": self.n_fillet_root, "C": n_rim}[block[0]]
        return ni, self.n_half(side)


@dataclass(frozen=True, eq=False)
class ToothGeometry:
    """Exact boundary curves of a gear's reference tooth body and its six blocks at levels z."""

    gear: Gear
    rim_depth: float  # [mm] below the root circle (outside it for internal gears)

    def __post_init__(self):
        g = self.gear
        if not (0 < self.rim_depth):
            raise InputError("mesh.rim_depth_mm", self.rim_depth, "> 0 mm")
        if not g.internal and self.rim_depth >= 0.95 * g.r_root:
            raise InputError("mesh.rim_depth_mm", self.rim_depth, f"< {0.95 * g.r_root:.4g} mm (root radius of {g.name})")

    # ------------------------------------------------------------------ constants
    @property
    def kappa(self) -> int:
        return self.gear.kappa

    @property
    def r_rim(self) -> float:
        """Radius of the rim circle (bore of an external gear, outside of a ring) [mm]."""
        return self.gear.r_root - self.kappa * self.rim_depth

    @property
    def split_depth(self) -> float:
        """Depth d_M of the mid-surface end of the split surface below the root circle [mm]."""
        g = self.gear
        return min(g.r_root * math.sin(math.pi / g.teeth), 0.6 * self.rim_depth)

    def surf(self, side: int, piece: str):
        return self.gear.surface(side, piece)

    def flank_start(self, side: int) -> float:
        """Flank parameter where the tooth boundary leaves the fillet (:func:`mesher.region.fillet_start`) [mm]."""
        return fillet_start(self.gear, side)[0]

    def space_param(self) -> float:
        """Root parameter at the middle of the tooth space (-pi m / 2) [mm]."""
        return self.surf(1, "root").u_range[0]

    # ------------------------------------------------------------------ exact curves
    def space_centre(self, z) -> np.ndarray:
        """Point Q3 of side +1 (root circle, middle of the space) at levels z, (nz, 3) [mm]."""
        z = np.atleast_1d(np.asarray(z, float))
        return self.surf(1, "root").points(np.full_like(z, self.space_param()), z)

    def tip_u(self, side: int, z) -> np.ndarray:
        """Flank parameter u where the flank meets the tip circle |r_xy| = r_tip, per level z [mm]."""
        z = np.atleast_1d(np.asarray(z, float))
        g, s = self.gear, self.surf(side, "flank")
        u = np.full_like(z, g.area(side).u_tip)
        for it in range(40):
            sp = s.evaluate(u, z)
            rxy = np.hypot(sp.r[:, 0], sp.r[:, 1])
            f = rxy - g.r_tip
            df = (sp.r[:, 0] * sp.r_u[:, 0] + sp.r[:, 1] * sp.r_u[:, 1]) / rxy
            du = f / df
            u = u - du
            if np.all(np.abs(du) < 1e-13):
                break
        res = np.abs(np.hypot(*s.points(u, z)[:, :2].T) - g.r_tip)
        if not np.all(res < 1e-9):
            i = int(np.argmax(res))
            raise ConvergenceError(f"{g.name} tip of flank {side:+d}", f"z = {z[i]:.6g} mm", float(res[i]), it + 1)
        return u

    def flank_table(self, side: int, z_ref: float):
        """(u, arclength) along the flank at level z_ref, fillet start -> tip."""
        u0 = self.flank_start(side)
        u1 = float(self.tip_u(side, z_ref)[0])
        u = np.linspace(u0, u1, _TABLE)
        return u, _arclength(self.surf(side, "flank").points(u, np.full_like(u, z_ref)))

    def fillet_table(self, side: int, z_ref: float):
        """(angle, arclength, turning of the tangent [rad]) along the fillet from the flank to the root at z_ref."""
        w0 = self.surf(side, "fillet").u_range[0]
        w1 = fillet_start(self.gear, side)[1]
        w = np.linspace(w1, w0, _TABLE)
        p = self.surf(side, "fillet").points(w, np.full_like(w, z_ref))
        d = np.diff(p[:, :2], axis=0)
        ang = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))  # chord directions, at the chord midpoints
        turn = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(ang)))])
        turn = np.concatenate([[0.0], 0.5 * (turn[1:] + turn[:-1]), [turn[-1]]])  # at the samples
        return w, _arclength(p), turn

    def root_table(self, side: int, z_ref: float):
        """(u, arclength) along the root from the fillet to the space centre at z_ref."""
        u0, u1 = self.surf(side, "root").u_range
        u = np.linspace(u1, u0, _TABLE)
        return u, _arclength(self.surf(side, "root").points(u, np.full_like(u, z_ref)))

    def base_length(self, side: int, z_ref: float) -> float:
        """Length of the base line from the mid-surface to the start of the fillet at z_ref [mm]."""
        F = {s: self.surf(s, "flank").points(self.flank_start(s), z_ref) for s in SIDES}
        rq = 0.5 * (np.hypot(*F[1][:2]) + np.hypot(*F[-1][:2]))
        q3 = self.space_centre(z_ref)[0]
        thc = math.atan2(q3[1], q3[0]) - math.pi / self.gear.teeth
        q1 = np.array([rq * math.cos(thc), rq * math.sin(thc), z_ref])
        return float(np.linalg.norm(F[side] - q1))

    # ------------------------------------------------------------------ blocks
    def blocks(self, plan: ToothPlan, z: np.ndarray, rim_frac: np.ndarray) -> dict[str, np.ndarray]:
        """Nodes of the six blocks at levels z: name -> (nz, ni+1, nj+1, 3) [mm], gear frame."""
        g = self.gear
        z = np.asarray(z, float)
        nz = len(z)
        kap = self.kappa
        pitch = g.pitch_angle
        q3p = self.space_centre(z)
        thc = np.arctan2(q3p[:, 1], q3p[:, 0]) - math.pi / g.teeth  # tooth axis angle (nz,)
        q3m = q3p @ _rot(-pitch).T
        q3 = {1: q3p, -1: q3m}

        def polar(p):  # Cartesian (nz, n, 3) -> (r, theta - theta_c) (nz, n, 2)
            r = np.hypot(p[..., 0], p[..., 1])
            th = np.arctan2(p[..., 1], p[..., 0]) - thc[:, None]
            th = (th + math.pi) % (2 * math.pi) - math.pi
            return np.stack([r, th], -1)

        def zz(n):
            return np.broadcast_to(z[:, None], (nz, n))

        # exact boundary rows
        flank, fr, tip, F = {}, {}, {}, {}
        for s in SIDES:
            u_form = self.flank_start(s)
            ut = self.tip_u(s, z)
            scale = (ut - u_form) / (plan.u_tip_ref[s] - u_form)
            u = u_form + (plan.flank_u[s][None, :] - u_form) * scale[:, None]
            u[:, -1] = ut
            pf = self.surf(s, "flank").points(u, zz(u.shape[1]))
            w = np.broadcast_to(plan.fillet_w[s], (nz, len(plan.fillet_w[s])))
            pfi = self.surf(s, "fillet").points(w, zz(w.shape[1]))
            parts = [pfi]
            if len(plan.root_u[s]) > 1:
                ur = np.broadcast_to(plan.root_u[s], (nz, len(plan.root_u[s])))
                parts.append(self.surf(s, "root").points(ur, zz(ur.shape[1]))[:, 1:])
            pr = np.concatenate(parts, axis=1)
            pr[:, 0] = pf[:, 0]  # pieces join within 1e-10 mm: one node
            pr[:, -1] = q3[s]
            flank[s], fr[s] = polar(pf), polar(pr)
            tip[s], F[s] = flank[s][:, -1], flank[s][:, 0]

        r_q1 = 0.5 * (F[1][:, 0] + F[-1][:, 0])
        r_q3 = np.hypot(q3p[:, 0], q3p[:, 1])
        r_m = r_q3 - kap * self.split_depth
        r_in = self.r_rim
        room = kap * (r_m - r_in)
        if np.any(room < 0.2 * self.rim_depth):
            i = int(np.argmin(room))
            raise GeometryError(g.name, "rim too thin",
                                f"the split point M at z = {z[i]:.4g} mm is {room[i]:.4g} mm from the rim circle; "
                                f"increase mesh.rim_depth_mm (now {self.rim_depth:.4g} mm)")

        def line(r0, t0, r1, t1, f):  # polar straight line, fractions f (n,) -> (nz, n, 2)
            f = np.asarray(f, float)[None, :]
            return np.stack([r0[:, None] + f * (r1 - r0)[:, None], t0[:, None] + f * (t1 - t0)[:, None]], -1)

        zero = np.zeros(nz)
        rtip = np.full(nz, g.r_tip)
        rin = np.full(nz, r_in)
        midfrac_A = np.mean([_fractions(flank[s]) for s in SIDES], axis=0).mean(0)
        midfrac_B = np.mean([_fractions(fr[s]) for s in SIDES], axis=0).mean(0)
        th_q1 = 0.5 * (F[1][:, 1] + F[-1][:, 1])  # the mid-surface follows the tooth (crowned teeth twist)
        th_t = 0.5 * (tip[1][:, 1] + tip[-1][:, 1])
        midA = line(r_q1, th_q1, rtip, th_t, midfrac_A)
        midB = line(r_q1, th_q1, r_m, zero, midfrac_B)
        midC = line(r_m, zero, rin, zero, rim_frac)
        out = {}
        for s in SIDES:
            sg = "+" if s > 0 else "-"
            h = plan.half[s]
            nT = len(h) - 1
            base = line(r_q1, th_q1, F[s][:, 0], F[s][:, 1], h)
            uni = np.linspace(0.0, 1.0, nT + 1)
            top = line(rtip, th_t, rtip, tip[s][:, 1], uni)  # the narrow top land: no grading
            top[:, -1] = tip[s]
            q3s = polar(q3[s][:, None, :])[:, 0]
            # the split surface takes the base's grading (finest at the fillet): the layers under the whole fillet
            # and root, not only at the start of the fillet, are as thin as on the flank (docs/benchmarks.md,
            # "Third round: grading away from the zones": the fillet stress of a uniform split surface converged
            # at order 0.8, graded at order 2)
            diag = line(r_m, zero, q3s[:, 0], q3s[:, 1], h)
            space = line(q3s[:, 0], q3s[:, 1], rin, q3s[:, 1], rim_frac)
            rim = line(rin, zero, rin, q3s[:, 1], uni)
            for name, rows in (("A", (midA, flank[s], base, top)), ("B", (midB, fr[s], base, diag)),
                               ("C", (midC, space, diag, rim))):
                metric = tuple(_cart(e) for e in rows)
                P = tfi(*rows, metric=metric)
                out[name + sg] = _to_xyz(P, thc, z)
        return out


def _fractions(p):
    from mesher.tfi import arc_fractions

    return arc_fractions(_cart(p))


def _cart(p):
    return np.stack([p[..., 0] * np.cos(p[..., 1]), p[..., 0] * np.sin(p[..., 1])], -1)


def _to_xyz(P, thc, z):
    sh = (slice(None),) + (None,) * (P.ndim - 2)
    th = P[..., 1] + thc[sh]
    return np.stack([P[..., 0] * np.cos(th), P[..., 0] * np.sin(th), np.broadcast_to(z[sh], th.shape)], -1)
