r"""A pair's transmission error and contact at any angle, and the positions engineers name (one home).

Periodic TE (:class:`MeshTE`). A pair TCA (:func:`tca.pair.analysis.run_pair_tca`) solves the reference
pair of teeth on a grid of :math:`\phi_1`. Pair :math:`k` (tooth :math:`-k \bmod N` of each gear)
is the reference pair turned by :math:`k` pitches, so its TE is the reference branch shifted,
:math:`\Delta\phi_2^{(k)}(\phi_1) = \Delta\phi_2^{(0)}(\phi_1 - 2\pi k/N_1)`, and the pair in contact
is the one with the largest :math:`\Delta\phi_2` (the "largest Δφ" rule of section 1.4).

Contact at an angle (:func:`mesh_contact`). At :math:`\phi` the branch :math:`k` with the largest
value gives :math:`\phi_2 = (N_1/N_2)\phi + \Delta\phi_2`. On the grid the TCA solution is used as
it is; between grid points the reference solution is interpolated linearly (an initial gap of the
order of :math:`h^2 \max|\Delta\phi_2''|\,r/8`, far below the elastic approach).

Ties. Conjugate flanks (aligned involute gears without modifications) have equal TE on two pairs
in the double-contact zones. Branches within :data:`TIE_MM` (a separation of 1 nm at the driven
gear's arm) of the largest are tied; among them the pair whose reference solution is in contact at
the interpolation nodes and lies furthest inside its own contact interval is taken (at the HPSTC
the pair there, not the pair entering at the tooth tip).

Positions on the path of contact (:func:`path_of_contact`, transverse section at mid-face
:math:`z = 0`, ISO 6336-2 terminology). Operating pressure angle
:math:`\cos\alpha_{wt} = (r_{b2} \pm r_{b1})/a` (+ external, − internal), :math:`T_1` the tangent
point of the line of action on gear 1's base circle, :math:`t` the distance from :math:`T_1`
along it. With :math:`\overline{T_1T_2} = a \sin\alpha_{wt}`:

.. math::
    t_C = r_{b1}\tan\alpha_{wt},\quad
    t_A = \overline{T_1T_2} \mp \sqrt{r_{a2}^2 - r_{b2}^2}\ (\text{external } -,\ \text{internal: } \sqrt{\cdot} - \overline{T_1T_2}),\quad
    t_E = \sqrt{r_{a1}^2 - r_{b1}^2},

both clipped to the form circles (start of the fillets). The driving gear turns positively, so the
contact runs from :math:`A` (its root) to :math:`E` (its tip); with the base pitch
:math:`p_{bt} = 2\pi r_{b1}/N_1` the lowest point of single tooth contact on the driver is
:math:`t_B = t_E - p_{bt}` and the highest :math:`t_D = t_A + p_{bt}` (ISO 6336-3 loads the tooth
at :math:`D`). For involutes the contact moves along the line of action by :math:`r_{b1}\,d\phi_1`,
so the reference pair is at :math:`t` when :math:`\phi_1 = \phi_C + (t - t_C)/r_{b1}`, with
:math:`\phi_C` the angle at which the reference tooth's flank at :math:`z = 0` passes through the
pitch point :math:`C = (r_{w1}, 0, 0)`. The roll angle of a point is :math:`\xi = t / r_{b1}`.
For helical gears these are the positions of the contact line's crossing of the mid-face section.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from tca.contact.ellipse import contact_ellipse
from tca.errors import GeometryError, InputError
from tca.pair.gear_pair import GearPair
from tca.pair.result import ContactKind, PairTCAResult

__all__ = ["MeshTE", "MeshContact", "NeighbourContact", "mesh_contact", "PathOfContact", "path_of_contact", "NAMED", "GRID",
           "POSITIONS", "grid_index", "path_angle", "position_angle", "TIE_MM", "tied_branches"]

TIE_MM = 1e-6  # separation [mm] below which two pairs' TEs are equal (conjugate flanks; far below the elastic approach)
GRID = ("max_te", "min_te")  # positions read off the TCA grid
NAMED = ("pitch", "hpstc", "lpstc")  # positions on the path of contact
POSITIONS = GRID + NAMED


# ---------------------------------------------------------------------------------------------- periodic TE
@dataclass(frozen=True, eq=False)
class MeshTE:
    """Periodic TE of one mesh, Δφ2(φ1) [rad]: the largest of the reference branch shifted by pitches."""

    phi0: float  # first grid angle [rad]
    h: float  # grid step [rad]
    branch: np.ndarray  # Δφ on the grid, -inf where the reference pair is out of contact [rad]
    kind: np.ndarray  # ContactKind on the grid
    pitch: float  # angular pitch of the driving gear [rad]
    result: PairTCAResult

    @classmethod
    def from_result(cls, r: PairTCAResult) -> "MeshTE":
        """Branch of the reference pair, completed for interpolation near the changes of pair.

        Where the pair TCA skipped the bounded-contact search because the pair's tangency (an upper
        bound of its contact) lies below the other pairs, the tangency is kept: the branch stays below
        the envelope there, and interpolation next to a change of pair keeps its O(h^2) accuracy.
        """
        ref = r.reference
        ratio = r.pair.ratio
        te = ref.phi2 - ratio * ref.phi1
        h = (ref.phi1[-1] - ref.phi1[0]) / (len(ref.phi1) - 1)
        pitch = 2 * math.pi / r.pair.gear1.teeth
        bare = cls(float(ref.phi1[0]), float(h), te, ref.kind.copy(), pitch, r)
        env = bare.branches(ref.phi1)[0].max(1)
        tan = np.where(ref.tangency & ~ref.out_of_mesh, ref.x[:, 4] - ratio * ref.phi1, -np.inf)
        keep = ~np.isfinite(te) & (tan <= env + 1e-12)
        return cls(float(ref.phi1[0]), float(h), np.where(keep, tan, te), ref.kind.copy(), pitch, r)

    def branches(self, phi) -> tuple[np.ndarray, np.ndarray]:
        """Values (m, K) of the shifted branches at phi (m,) and their pair indices (K,)."""
        phi = np.asarray(phi, float)
        n = len(self.branch)
        lo, hi = self.phi0, self.phi0 + (n - 1) * self.h
        kmin = int(math.floor((phi.min() - hi) / self.pitch)) - 1
        kmax = int(math.ceil((phi.max() - lo) / self.pitch)) + 1
        ks = np.arange(kmin, kmax + 1)
        t = (phi[:, None] - ks[None, :] * self.pitch - self.phi0) / self.h
        tr = np.round(t)
        t = np.where(np.abs(t - tr) < 1e-7, tr, t)  # on the grid: exact nodal values
        i0 = np.floor(t).astype(int)
        w = t - i0
        ok0 = (i0 >= 0) & (i0 < n)
        ok1 = (i0 + 1 >= 0) & (i0 + 1 < n)
        y0 = np.where(ok0, self.branch[np.clip(i0, 0, n - 1)], -np.inf)
        y1 = np.where(ok1, self.branch[np.clip(i0 + 1, 0, n - 1)], -np.inf)
        with np.errstate(invalid="ignore"):
            val = np.where(w == 0, y0, np.where(np.isfinite(y0) & np.isfinite(y1), (1 - w) * y0 + w * y1, -np.inf))
        return val, ks

    def __call__(self, phi) -> np.ndarray:
        """Δφ [rad] at phi (the pair with the largest Δφ is in contact)."""
        val, _ = self.branches(phi)
        out = val.max(1)
        if not np.all(np.isfinite(out)):
            bad = np.asarray(phi, float)[~np.isfinite(out)][0]
            p = self.result.pair
            raise GeometryError(f"{p.gear1.name}-{p.gear2.name}", "no contact",
                                f"no pair of teeth is in contact at phi = {math.degrees(bad):.6f} deg (contact ratio < 1)")
        return out

    def slope(self, k: int, phi: float) -> float:
        """dΔφ2/dφ1 [rad/rad] of branch k at phi: parabola through the three nearest grid values."""
        y = self.branch
        t = (phi - k * self.pitch - self.phi0) / self.h
        if not -0.5 <= t <= len(y) - 0.5:
            return float("nan")  # the branch is not defined at phi
        i = int(round(t))
        ok = lambda j: 0 <= j < len(y) and np.isfinite(y[j])  # noqa: E731
        if ok(i - 1) and ok(i) and ok(i + 1):
            d = 0.5 * (y[i + 1] - y[i - 1]) + (t - i) * (y[i + 1] - 2 * y[i] + y[i - 1])
        elif ok(i) and ok(i + 1):
            d = y[i + 1] - y[i]
        elif ok(i - 1) and ok(i):
            d = y[i] - y[i - 1]
        else:
            return float("nan")
        return float(d / self.h)


# ---------------------------------------------------------------------------------------------- contact at an angle
class NeighbourContact(NamedTuple):
    """Another pair of teeth at the angle of a :class:`MeshContact`: its branch ``k`` (teeth -k mod N),
    the reference pair's parameters (u1, v1, u2, v2) [mm] at phi1 - k p1, its contact kind, and its TCA
    separation [mm] from contact, (Δφ2 - Δφ2 of its branch) |arm 2| (the arm of the pair in contact).

    Kind NONE: the extended surfaces touch outside a working area (beyond a tip or a face end); the
    parameters are that point's and the separation is a lower bound of the real one (the pair can only
    touch at the boundary nearest to it, e.g. a tip edge)."""

    k: int
    params: tuple
    kind: int
    gap: float


@dataclass(frozen=True, eq=False)
class MeshContact:
    """Contact of a meshing pair at an angle of its driving gear, in the pair frame."""

    k: int  # pair in contact: tooth -k mod N of each gear
    phi1: float  # [rad]
    phi2: float  # [rad]
    te: float  # Δφ2 [rad]
    params: tuple  # (u1, v1, u2, v2) [mm] on the reference teeth
    kind: int  # ContactKind
    point: np.ndarray  # contact point [mm]
    normal: np.ndarray  # unit normal out of gear 1's tooth
    curvature: tuple  # (λ1, λ2) eigenvalues of K2 - K1 [1/mm]
    angle: float  # major axis from the projected gear-1 axis [rad]
    exact: bool  # on the TCA grid
    slope: float = 0.0  # dΔφ2/dφ1 of the pair in contact [rad/rad]
    arms: tuple = (0.0, 0.0)  # moment arms ((x - o_i) x n) . a_i of the normal about both axes [mm]
    next_gap: float = math.inf  # [mm] TCA separation of the next pair of teeth, (Δφ2 - Δφ2 of the next branch) |arm 2|
    slopes: dict = field(default_factory=dict)  # offset q -> dΔφ2/dφ1 of the pair q teeth on (branch k - q)
    tied: tuple = ()  # offsets q of other pairs in contact with a TE equal to this one's (within TIE_MM)
    others: tuple = ()  # NeighbourContact of every other pair of teeth with a reference contact at this angle

    @property
    def ratio(self) -> float:
        """Instantaneous ratio dφ2/dφ1 = N1/N2 + dΔφ2/dφ1 of the pair in contact."""
        return self.arms[0] / self.arms[1] if self.arms[1] else float("nan")

    def ratio_of(self, q: int) -> float:
        """Instantaneous ratio of the pair of teeth at offset q from the pair in contact (nan: not on its branch)."""
        return self.ratio + self.slopes.get(q, float("nan")) - self.slope if q else self.ratio


def _grid_place(ref, phi: float, k: int, pitch: float) -> tuple[int, float, bool]:
    """(i0, w, exact): grid interval of the reference solution for pair k at phi."""
    n = len(ref.phi1)
    h = (ref.phi1[-1] - ref.phi1[0]) / (n - 1)
    t = (phi - k * pitch - ref.phi1[0]) / h
    tr = round(t)
    if abs(t - tr) < 1e-7:
        return int(tr), 0.0, True
    i0 = int(math.floor(t))
    return i0, t - i0, False


def _usable(ok: np.ndarray, i0: int, w: float) -> bool:
    n = len(ok)
    if not (0 <= i0 < n and ok[i0]):
        return False
    return w == 0.0 or (i0 + 1 < n and ok[i0 + 1])


def _depth(ok: np.ndarray, i0: int) -> int:
    """Grid steps from i0 to the nearer end of its run of contact (how far inside its contact interval)."""
    lo = i0
    while lo > 0 and ok[lo - 1]:
        lo -= 1
    hi = i0
    while hi < len(ok) - 1 and ok[hi + 1]:
        hi += 1
    return min(i0 - lo, hi - i0)


def tied_branches(pair: GearPair, val: np.ndarray) -> np.ndarray:
    """Mask of the branch values ``val`` [rad] (one angle) within :data:`TIE_MM` of the largest, measured at
    the driven gear's pitch radius (a length scale for the tie test)."""
    with np.errstate(invalid="ignore"):
        return np.isfinite(val) & ((np.max(val) - val) * max(pair.gear2.r_p, 1.0) <= TIE_MM)


def mesh_contact(result: PairTCAResult, phi: float) -> MeshContact:
    """The contact of a pair TCA's drive at driving-gear angle ``phi`` [rad] (module docstring)."""
    pair = result.pair
    mte = MeshTE.from_result(result)
    val, ks = mte.branches(np.array([phi], float))
    val = val[0]
    top = float(val.max())
    name = f"{pair.gear1.name}-{pair.gear2.name}"
    if not math.isfinite(top):
        raise GeometryError(name, "no contact", f"no pair of teeth is in contact at phi = {math.degrees(phi):.6f} deg")
    ref = result.reference
    ok = (ref.kind != ContactKind.NONE) & np.all(np.isfinite(ref.x), axis=1)
    p1, p2 = 2 * math.pi / pair.gear1.teeth, 2 * math.pi / pair.gear2.teeth
    tied = [int(q) for q in np.flatnonzero(tied_branches(pair, val))]
    cands = []
    for q in tied:
        i0, w, ex = _grid_place(ref, phi, int(ks[q]), p1)
        if _usable(ok, i0, w):
            cands.append((_depth(ok, i0), float(val[q]), q, i0, w, ex))
    if not cands:
        raise GeometryError(name, "no contact", f"the pair of largest TE ({', '.join(str(int(ks[q])) for q in tied)}) "
                            f"has no reference contact at phi = {math.degrees(phi):.6f} deg")
    _, te, q, i0, w, exact = max(cands)
    k = int(ks[q])
    # the next pair: the largest other branch (a tangency of the extended surfaces is an upper bound of that
    # pair's TE, so the gap is a lower bound), except tangency-only branches tied with this one: the extended
    # surfaces of conjugate flanks touch outside the working areas, which says nothing of the real gap
    te_next = -math.inf
    for j in range(len(ks)):
        if j != q and math.isfinite(val[j]):
            i0j, wj, _ = _grid_place(ref, phi, int(ks[j]), p1)
            near = any(0 <= i < len(ok) and ok[i] for i in ((i0j, i0j + 1) if wj > 0 else (i0j,)))
            if near or j not in tied:  # a tied pair at an end of its own contact (a tip) does touch
                te_next = max(te_next, float(val[j]))
    if w > 0:
        x = (1 - w) * ref.x[i0] + w * ref.x[i0 + 1]
        kind = int(ref.kind[i0] if w < 0.5 else ref.kind[i0 + 1])
    else:
        x, kind = ref.x[i0].copy(), int(ref.kind[i0])
    phi2 = pair.ratio * phi + te
    f1, f2 = pair.flanks()
    m1, m2 = f1.mount, f2.mount
    w1, _, _ = f1.world(np.array([x[0]]), np.array([x[1]]), np.array([phi - k * p1]))
    w2, _, _ = f2.world(np.array([x[2]]), np.array([x[3]]), np.array([phi2 - k * p2]))
    _, _, ang, lam = contact_ellipse(w1, w2, 1.0, m1.axis[None, :])
    x0, n0 = w1.r[0].copy(), w1.n[0].copy()
    arms = tuple(float(np.cross(x0 - m.origin, n0) @ m.axis) for m in (m1, m2))
    also = tuple(sorted(int(k - ks[c[2]]) for c in cands if c[2] != q))
    others = []
    solved = np.all(np.isfinite(ref.x), axis=1)  # a contact, or a tangency of the extended surfaces (kind NONE)
    for j in range(len(ks)):
        if j == q or not math.isfinite(val[j]):
            continue
        i0j, wj, _ = _grid_place(ref, phi, int(ks[j]), p1)
        if not _usable(solved, i0j, wj):
            continue
        xj = (1 - wj) * ref.x[i0j] + wj * ref.x[i0j + 1] if wj > 0 else ref.x[i0j]
        kj = int(ref.kind[i0j] if wj < 0.5 else ref.kind[i0j + 1])
        others.append(NeighbourContact(int(ks[j]), tuple(float(v) for v in xj[:4]), kj,
                                       (te - float(val[j])) * abs(arms[1])))
    return MeshContact(k, float(phi), float(phi2), te, tuple(float(v) for v in x[:4]), kind, x0, n0,
                       (float(lam[0, 0]), float(lam[0, 1])), float(ang[0]), exact, mte.slope(k, phi), arms,
                       (te - te_next) * abs(arms[1]), {j: mte.slope(k - j, phi) for j in range(-4, 5)}, also,
                       tuple(sorted(others, key=lambda o: o.gap)))


# ---------------------------------------------------------------------------------------------- path of contact
@dataclass(frozen=True)
class PathOfContact:
    """Path of contact of an aligned pair in the transverse section z = 0 (module docstring) [mm, rad]."""

    r_b1: float  # base radius of the driving gear [mm]
    alpha_wt: float  # operating transverse pressure angle [rad]
    t_a: float  # start of active contact (driver's root) from T1 [mm]
    t_b: float  # lowest point of single tooth contact on the driver [mm]
    t_c: float  # pitch point [mm]
    t_d: float  # highest point of single tooth contact on the driver [mm]
    t_e: float  # end of active contact (driver's tip) [mm]
    p_bt: float  # transverse base pitch [mm]
    phi_c: float  # driver angle at which the reference pair touches at C (z = 0) [rad]

    @property
    def contact_ratio(self) -> float:
        """Transverse contact ratio ε_α = (t_E - t_A) / p_bt."""
        return (self.t_e - self.t_a) / self.p_bt

    def phi1(self, t: float) -> float:
        """Driver angle [rad] at which the reference pair touches at distance t [mm] from T1 (z = 0)."""
        return self.phi_c + (t - self.t_c) / self.r_b1

    def t(self, name: str) -> float:
        """Distance from T1 [mm] of a named position ('pitch', 'hpstc', 'lpstc')."""
        return {"pitch": self.t_c, "hpstc": self.t_d, "lpstc": self.t_b}[name]


def path_of_contact(pair: GearPair) -> PathOfContact:
    """Points A, B, C, D, E of the path of contact of an aligned involute pair (module docstring)."""
    g1, g2 = pair.gear1, pair.gear2
    if g1.internal:
        raise InputError("position", "path of contact", "a pair driven by an external gear (gear 1 internal is not covered)")
    a = pair.E + pair.misalignment.d_center
    rb1, rb2 = g1.r_b, g2.r_b
    c = (rb2 - rb1) / a if g2.internal else (rb1 + rb2) / a
    if not 0 < c < 1:
        raise InputError("center_distance_mm", a, "a centre distance with an operating pressure angle in (0, 90) deg")
    al = math.acos(c)
    t12 = a * math.sin(al)
    s = lambda r, rb: math.sqrt(max(r * r - rb * rb, 0.0))  # noqa: E731
    a1, a2 = g1.area(pair.side1), g2.area(pair.side2)
    if g2.internal:
        t_a = s(g2.r_tip, rb2) - t12
        t_e = min(s(g1.r_tip, rb1), s(a2.r_form, rb2) - t12)
    else:
        t_a = t12 - s(g2.r_tip, rb2)
        t_e = min(s(g1.r_tip, rb1), t12 - s(a2.r_form, rb2))
    t_a = max(t_a, s(a1.r_form, rb1))
    p_bt = 2 * math.pi * rb1 / g1.teeth
    t_c = rb1 * math.tan(al)
    # the reference tooth's flank at the operating pitch radius, z = 0, in its gear frame
    r_w = rb1 / c
    u = g1.u_at_radius(pair.side1, r_w)
    gp = g1.profile(pair.side1, np.array(u))[0]
    th = math.atan2(float(gp[1]), float(gp[0]))
    m1, _ = pair.mounts()
    cw = m1.R0.T @ (np.array([r_w, 0.0, 0.0]) - m1.origin)
    phi_c = math.atan2(float(cw[1]), float(cw[0])) - th - m1.phase
    return PathOfContact(rb1, al, t_a, t_e - p_bt, t_c, t_a + p_bt, t_e, p_bt, phi_c)


# ---------------------------------------------------------------------------------------------- positions
def grid_index(te: np.ndarray, position) -> int:
    """Index of a position on a TCA grid: 'max_te', 'min_te' or an integer index (negative: from the end).

    The last point of a periodic grid repeats the first, so the extremes are searched without it.
    """
    te = np.asarray(te, float)
    n = len(te)
    body = te[:-1] if n > 1 else te
    if position == "max_te":
        return int(np.argmax(body))
    if position == "min_te":
        return int(np.argmin(body))
    if isinstance(position, bool) or not isinstance(position, (int, np.integer)) or not -n <= position < n:
        raise InputError("position", position, f"an integer index in [{-n}, {n - 1}] (negative: from the end), "
                         + ", ".join(repr(p) for p in POSITIONS))
    return int(position) % n


def path_angle(pair: GearPair, position, roll: float | None = None) -> float:
    """Driver angle φ1 [rad] of a named position or a roll angle ξ [rad] (distance from T1 over r_b1).

    Needs the pair only, so a case checks it before any work; a position outside the path of contact
    (or a single-contact limit of a pair with ε_α < 1) is an InputError.
    """
    path = path_of_contact(pair)
    if roll is not None:
        t = roll * path.r_b1
        if not path.t_a - 1e-9 <= t <= path.t_e + 1e-9:
            raise InputError("roll_deg", math.degrees(roll), f"in [{math.degrees(path.t_a / path.r_b1):.4f}, "
                             f"{math.degrees(path.t_e / path.r_b1):.4f}] deg (the driver's roll angles on the path of contact)")
        return path.phi1(t)
    if position not in NAMED:
        raise InputError("position", position, ", ".join(repr(p) for p in NAMED) + " (positions on the path of contact)")
    if path.contact_ratio < 1.0 and position != "pitch":
        raise InputError("position", position, f"'pitch' only: the transverse contact ratio "
                         f"{path.contact_ratio:.3f} < 1 has no single-tooth-contact limits")
    t = path.t(position)
    if not path.t_a - 1e-9 <= t <= path.t_e + 1e-9:
        raise InputError("position", position, f"a point on the path of contact, t in [{path.t_a:.4f}, "
                         f"{path.t_e:.4f}] mm from T1 (it is at {t:.4f} mm)")
    return path.phi1(t)


def position_angle(result: PairTCAResult, position="max_te", phi1: float | None = None,
                   roll: float | None = None) -> float:
    """Driver angle φ1 [rad] of a position: a grid position, a named one (:func:`path_angle`), ``phi1`` or a roll angle [rad]."""
    if phi1 is not None and roll is not None:
        raise InputError("roll_deg", math.degrees(roll), "either phi1_deg or roll_deg, not both")
    if phi1 is not None:
        return float(phi1)
    if roll is not None or position in NAMED:
        return path_angle(result.pair, position, roll)
    return float(result.phi1[grid_index(result.te, position)])
