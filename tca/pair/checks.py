r"""Can the two gears of a pair mesh at their centre distance? Checked before any TCA, mesh or solve.

Every check is gear geometry in the transverse section (notation of :mod:`tca.geometry.involute`:
:math:`r_{bi}` base, :math:`r_{ai}` tip, :math:`r_{fi}` root radius, :math:`r_{Fi}` the form circle
where the generated fillet meets the working flank, :math:`a` the centre distance, :math:`\alpha_w`
the transverse working pressure angle). They run in this order, and the first that fails raises an
:class:`~tca.errors.InputError` naming the key to change, its value and the value that fits:

1. **The pair can mesh** (:func:`check_meshing`): equal normal base pitches
   :math:`p_{bn} = \pi m_n\cos\alpha_n` and equal transverse base pitches :math:`p_{bt} = 2\pi r_b/z` (C1),
   each within :data:`BASE_PITCH_TOL` of the pitch (a single-pitch deviation inside the tolerance
   classes of ISO 1328-1) plus the profile modifications declared on the gears (tip relief
   :math:`C_a`, the parabolic rack's deviation at the tip), which absorb a mismatch at the
   transfer of load. Screw parameters may differ where ``reference_helix`` keeps the transverse
   geometry common: a lead mismatch of at most :data:`LEAD_MISMATCH_DEG` (the report's 10.25 / 10 /
   9.75 deg train differs by 0.25 deg). Helical hands: opposite for an external mesh, equal for an
   internal one (:class:`tca.pair.gear_pair.GearPair`).
2. **The centre distance**: without ``center_distance_mm`` the pair runs at the zero-backlash
   operating centre distance of its profile shifts (inv :math:`\alpha_w`, (I3)-(I4) of
   :mod:`tca.geometry.involute`); a given one (plus a misalignment ``d_center``) must leave the
   backlash (I2) :math:`j_t \ge 0` (C2), otherwise the error names the zero-backlash value.
3. **Tip-root clearance** :math:`c \ge 0` (C3): external :math:`a - r_{a1} - r_{f2}` and
   :math:`a - r_{a2} - r_{f1}`; internal (gear 2 the ring) :math:`r_{f2} - a - r_{a1}` and
   :math:`r_{a2} - a - r_{f1}`.
4. **Tip-fillet interference** along the line of action (C4): with
   :math:`\overline{T_1T_2} = a\sin\alpha_w` and the roll distances :math:`\rho = \sqrt{r^2 - r_b^2}`,
   the tip of one gear meets the other at :math:`\rho = \overline{T_1T_2} - \rho_{a,\text{tip gear}}`
   (external) or :math:`\rho_{a1} + \overline{T_1T_2}` / :math:`\rho_{a2} - \overline{T_1T_2}`
   (internal, pinion 1 / ring 2); that point must lie on the working flank, between the form
   circle :math:`r_F` and the tip. The error names the addendum that fits.
5. **Trochoid interference** (C5): the tip corners of each gear (transverse section :math:`z = 0`,
   the generated profile with its modifications) follow the relative motion
   :math:`\phi_2 = (z_1/z_2)\phi_1 \pm j_t/(2 r_{w2})` (either flank in contact) through the whole
   engagement, outside the line of action as well; their largest penetration into the mate's tooth
   (flank, fillet, root) must stay below :data:`PENETRATION_TOL` modules.
6. **Contact ratio** (C6): :math:`\varepsilon_\alpha = (t_E - t_A)/p_{bt}` on the path of contact
   clipped to the form circles, :math:`\varepsilon_\beta = b\sin\beta/(\pi m_n)`; below
   :math:`\varepsilon_\gamma = \varepsilon_\alpha + \varepsilon_\beta < 1` a warning says that the
   load passes over the tips between pairs.

Plausibility of each gear alone (module, angles, face width) is read with the case file
(:mod:`pipelines.cases.reader`); this module checks the pair.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace

import numpy as np

from tca.errors import GeometryError, InputError
from tca.geometry.gear import Gear
from tca.geometry.involute import backlash, inv, standard_center_distance, working_pressure_angle
from tca.geometry.profile import envelope_profile
from tca.pair.gear_pair import GearPair, Misalignment

__all__ = ["PairGeometry", "check_pair", "check_meshing", "BASE_PITCH_TOL", "LEAD_MISMATCH_DEG", "PENETRATION_TOL",
           "contact_ratios"]

BASE_PITCH_TOL = 0.005  # relative base-pitch mismatch allowed besides the declared modifications
LEAD_MISMATCH_DEG = 1.0  # screw parameters may differ by this helix angle when the transverse geometry is common
PENETRATION_TOL = 1e-3  # [modules] depth of a tip corner inside the mate counted as interference
BACKLASH_TOL = 1e-6  # [mm] rounding of the closed forms


@dataclass(frozen=True)
class PairGeometry:
    """What the checks found: centre distances [mm], working pressure angle [rad], backlash and clearances [mm],
    contact ratios and the warnings (text) of a pair that passed."""

    center_distance: float  # the one analysed (before misalignment)
    source: str  # 'given', 'standard' (no profile shifts) or 'zero backlash' (inv alpha_w of the shifts)
    standard_center_distance: float
    zero_backlash_center_distance: float
    working_pressure_angle: float
    backlash: float
    clearance: tuple  # (tip of gear 1 - root of gear 2, tip of gear 2 - root of gear 1)
    transverse_contact_ratio: float
    overlap_ratio: float
    warnings: tuple = ()

    @property
    def contact_ratio(self) -> float:
        """Total contact ratio eps_gamma = eps_alpha + eps_beta."""
        return self.transverse_contact_ratio + self.overlap_ratio

    def summary(self) -> dict:
        """JSON-ready record (units in the names)."""
        return {"center_distance_mm": self.center_distance, "center_distance_source": self.source,
                "standard_center_distance_mm": self.standard_center_distance,
                "zero_backlash_center_distance_mm": self.zero_backlash_center_distance,
                "working_pressure_angle_deg": math.degrees(self.working_pressure_angle),
                "backlash_mm": self.backlash, "tip_root_clearance_mm": list(self.clearance),
                "transverse_contact_ratio": self.transverse_contact_ratio, "overlap_ratio": self.overlap_ratio,
                "contact_ratio": self.contact_ratio, "warnings": list(self.warnings)}


def _key(g: Gear, key: str) -> str:
    return f"{g.name}.{key}"


def _modification_allowance(g: Gear) -> float:
    """Profile modifications at the tip [mm] that absorb a base-pitch mismatch: tip relief C_a, parabolic rack."""
    c = g.tip_relief.amount if g.tip_relief is not None else 0.0
    h = (g.addendum + g.profile_shift) * g.module / math.cos(g.pressure_angle)  # rack flank length to the tip
    a_c = max(g.parabola_pos, g.parabola_neg)
    return c + a_c * (h + abs(g.parabola_apex)) ** 2


def check_meshing(g1: Gear, g2: Gear) -> None:
    """Base pitches and leads that can mesh (C1 of the module docstring); InputError naming gear 2's key."""
    allow = BASE_PITCH_TOL + 0.0
    mods = _modification_allowance(g1) + _modification_allowance(g2)
    pbn1 = math.pi * g1.module * math.cos(g1.pressure_angle)
    pbn2 = math.pi * g2.module * math.cos(g2.pressure_angle)
    tol = allow * pbn1 + mods
    if abs(pbn1 - pbn2) > tol:
        if abs(g1.module - g2.module) > 1e-12 * g1.module or g1.pressure_angle == g2.pressure_angle:
            key, value = _key(g2, "module_mm"), g2.module
            fit = pbn1 / (math.pi * math.cos(g2.pressure_angle))
            valid = f"{fit:.6g} mm, the normal module of {g1.name} (with pressure angle {math.degrees(g2.pressure_angle):g} deg)"
        else:
            key, value = _key(g2, "pressure_angle_deg"), math.degrees(g2.pressure_angle)
            valid = f"{math.degrees(g1.pressure_angle):g} deg, the pressure angle of {g1.name}"
        raise InputError(key, value, valid,
                         f"normal base pitches pi m_n cos alpha_n = {pbn1:.4f} and {pbn2:.4f} mm differ by "
                         f"{abs(pbn1 - pbn2):.4f} mm > {tol:.4f} mm: these gears cannot mesh")
    pbt1 = 2 * math.pi * g1.r_b / g1.teeth
    pbt2 = 2 * math.pi * g2.r_b / g2.teeth
    tol_t = allow * pbt1 + mods
    if abs(pbt1 - pbt2) > tol_t:
        key = "reference_helix_deg" if (g1.reference_helix is not None or g2.reference_helix is not None) else "helix_deg"
        raise InputError(_key(g2, key), math.degrees(g2.beta_ref), f"{math.degrees(g1.beta_ref):g} deg, the transverse "
                         f"geometry of {g1.name} (helix_deg, or reference_helix_deg when the screw parameters differ)",
                         f"transverse base pitches {pbt1:.4f} and {pbt2:.4f} mm differ by {abs(pbt1 - pbt2):.4f} mm "
                         f"> {tol_t:.4f} mm: these gears cannot mesh")
    lead = abs(math.degrees(g1.helix - g2.helix))
    if lead > LEAD_MISMATCH_DEG:
        raise InputError(_key(g2, "helix_deg"), math.degrees(g2.helix),
                         f"{math.degrees(g1.helix):g} deg (the helix of {g1.name}) within {LEAD_MISMATCH_DEG:g} deg "
                         f"(a lead mismatch; the report's train differs by 0.25 deg)",
                         f"helix angles differ by {lead:.3g} deg: the teeth would touch at one corner only")


def _rho(r: float, rb: float) -> float:
    return math.sqrt(max(r * r - rb * rb, 0.0))


def _roles(pair: GearPair):
    """(external gear, internal gear or None)."""
    g1, g2 = pair.gear1, pair.gear2
    if g1.internal:
        return g2, g1
    if g2.internal:
        return g1, g2
    return g1, None


def _addendum_for_tip(g: Gear, r_tip: float) -> float:
    """The addendum h_a/m that puts gear g's tip circle at r_tip [mm]."""
    return g.kappa * (r_tip - g.r_p) / g.module - g.profile_shift


def _form(g: Gear) -> float:
    """Form circle [mm]: the start of the fillet, the one nearer the tip over both flanks."""
    rf = [g.area(s).r_form for s in (1, -1)]
    return max(rf) if g.kappa > 0 else min(rf)


def _clearance(pair: GearPair, a: float) -> tuple[float, float]:
    g1, g2 = pair.gear1, pair.gear2
    ext, intl = _roles(pair)
    if intl is None:
        return a - g1.r_tip - g2.r_root, a - g2.r_tip - g1.r_root
    c_ext = intl.r_root - a - ext.r_tip  # tip of the external gear against the internal gear's root
    c_int = intl.r_tip - a - ext.r_root  # tip of the internal gear against the external gear's root
    return (c_ext, c_int) if intl is g2 else (c_int, c_ext)


def _check_clearance(pair: GearPair, a: float, cd_key: str) -> tuple[float, float]:
    c = _clearance(pair, a)
    for g, other, ci in ((pair.gear1, pair.gear2, c[0]), (pair.gear2, pair.gear1, c[1])):
        if ci < -BACKLASH_TOL:
            r_fit = g.r_tip + g.kappa * ci  # the tip circle that just clears the mate's root circle
            fit = _addendum_for_tip(g, r_fit)
            raise InputError(_key(g, "addendum"), g.addendum, f"<= {fit:.4f} (tip shortening), or a larger {cd_key}",
                             f"the tip circle of {g.name} (r_a = {g.r_tip:.4f} mm) reaches {-ci:.4f} mm into the root "
                             f"circle of {other.name} (r_f = {other.r_root:.4f} mm) at the centre distance {a:.4f} mm")
    return c


def _path(pair: GearPair, a: float, aw: float):
    """Roll distances on the line of action (from gear 1's tangent point): the tips, the form circles [mm]."""
    g1, g2 = pair.gear1, pair.gear2
    t12 = a * math.sin(aw)
    rb1, rb2 = g1.r_b, g2.r_b
    ext, intl = _roles(pair)
    if intl is None:  # gear 2's roll distance from T2 is t12 - t
        return {"tip1": _rho(g1.r_tip, rb1), "tip2": t12 - _rho(g2.r_tip, rb2),
                "form1": _rho(_form(g1), rb1), "form2": t12 - _rho(_form(g2), rb2)}
    # internal: gear 2's roll distance from T2 is t + t12 (gear 2 the ring) or t - t12 (gear 1 the ring)
    s = 1.0 if intl is g2 else -1.0
    return {"tip1": _rho(g1.r_tip, rb1), "tip2": _rho(g2.r_tip, rb2) - s * t12,
            "form1": _rho(_form(g1), rb1), "form2": _rho(_form(g2), rb2) - s * t12}


def _tip_below_form(pair: GearPair, a: float, aw: float, tip_gear: Gear) -> tuple[bool, float]:
    """C4 for involute flanks: does the tip of ``tip_gear`` meet the mate's flank beyond its form circle on the line
    of action; and the radius it meets there [mm]."""
    g1 = pair.gear1
    p = _path(pair, a, aw)
    ext, intl = _roles(pair)
    ring1 = intl is not None and intl is g1  # gear 1 the ring: its roll distances grow toward its root
    if tip_gear is g1:
        bad = p["tip1"] < p["form2"] - 1e-9 if ring1 else p["tip1"] > p["form2"] + 1e-9
        mate, t = pair.gear2, p["tip1"]
    else:
        bad = p["tip2"] > p["form1"] + 1e-9 if ring1 else p["tip2"] < p["form1"] - 1e-9
        mate, t = g1, p["tip2"]
    t12 = a * math.sin(aw)
    return bad, math.hypot(mate.r_b, _mate_rho(pair, mate, t, t12))


def _mate_rho(pair: GearPair, mate: Gear, t: float, t12: float) -> float:
    """Roll distance on `mate` of the point at gear 1's roll distance t."""
    if mate is pair.gear1:
        return t
    ext, intl = _roles(pair)
    if intl is None:
        return t12 - t
    return t + t12 if intl is pair.gear2 else t - t12


def contact_ratios(pair: GearPair, a: float, aw: float) -> tuple[float, float]:
    """(eps_alpha, eps_beta) on the path clipped to the tips and form circles (C6)."""
    g1, g2 = pair.gear1, pair.gear2
    p = _path(pair, a, aw)
    ext, intl = _roles(pair)
    if intl is not None and intl is g1:
        length = min(p["form1"], p["tip2"]) - max(p["tip1"], p["form2"])
    else:
        length = min(p["tip1"], p["form2"]) - max(p["tip2"], p["form1"])
    pbt = 2 * math.pi * g1.r_b / g1.teeth
    eb = min(g1.face_width, g2.face_width) * math.sin(g1.helix) / (math.pi * g1.module)
    return max(length, 0.0) / pbt, eb


# ---------------------------------------------------------------------------------------------- C5: tip corners
@dataclass(frozen=True, eq=False)
class _Outline:
    """Half-thickness angle theta(r) [rad] of each flank (side +1, -1) on its fillet and flank, and the radii."""

    gear: Gear
    r: dict  # side -> radii, ascending
    theta: dict  # side -> half-thickness angles at those radii
    corners: np.ndarray  # (2, 2) tip corners (x, y) of the reference tooth, sides +1 and -1, gear frame

    def depth(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """How deep points (gear frame, z = 0) lie inside the toothed body [mm] (negative: outside)."""
        g = self.gear
        r = np.hypot(x, y)
        pitch = g.pitch_angle
        psi = np.arctan2(y, x)
        rel = psi - pitch * np.round(psi / pitch)
        out = np.full(r.shape, -np.inf)
        for side in (1, -1):
            sel = (rel >= 0) if side > 0 else (rel < 0)
            rr, th = self.r[side], self.theta[side]
            inside_r = (r >= rr[0]) & (r <= rr[-1])
            t = np.interp(r, rr, th)
            d = np.where(sel & inside_r, r * (t - np.abs(rel)), -np.inf)
            out = np.maximum(out, d)
        root = g.r_root
        body = (root - r) if g.kappa > 0 else (r - root)  # the rim below the root circle
        return np.maximum(out, body)


def _outline(g: Gear) -> _Outline:
    r, th, corners = {}, {}, []
    stretch = 1.0 / math.cos(g.beta_ref)
    for side in (1, -1):
        seg = g.segments(side)
        ar = g.area(side)
        pts = []
        for piece in ("fillet", "flank"):
            s = seg[piece]
            t1 = min(s.t1, ar.u_tip) if piece == "flank" else s.t1
            t = np.linspace(s.t0, t1, 1200)
            pts.append(envelope_profile(s, t, g.r_p, g.kappa, stretch)[0])
        p = np.concatenate(pts)
        rad = np.hypot(p[:, 0], p[:, 1])
        ang = np.arctan2(p[:, 1], p[:, 0])
        order = np.argsort(rad)
        r[side], th[side] = rad[order], ang[order]
        tip = envelope_profile(seg["flank"], np.array([ar.u_tip]), g.r_p, g.kappa, stretch)[0][0]
        corners.append((tip[0], side * tip[1]))
    return _Outline(g, r, th, np.array(corners))


def _worst_penetration(mover: _Outline, mate: _Outline, pair: GearPair, offsets) -> tuple[float, float]:
    """Largest depth [mm] of `mover`'s tip corners inside `mate` over the engagement, and the mover's angle there.

    ``offsets``: turns of gear 2 [rad] added to phi2 = (z1/z2) phi1 (each flank in contact in turn)."""
    m1, m2 = pair.mounts()
    mover_is_1 = mover.gear is pair.gear1
    mm, mt = (m1, m2) if mover_is_1 else (m2, m1)
    band = sorted((mate.gear.r_root, mate.gear.r_tip))
    margin = 0.5 * mate.gear.module
    coarse = np.linspace(-math.pi, math.pi, 7201)
    worst, where = -np.inf, 0.0

    def world(c3, phi):
        R, _ = mm.rotation(phi)
        return np.einsum("...ij,j->...i", R, c3) + mm.origin

    for corner in mover.corners:
        c3 = np.array([corner[0], corner[1], 0.0])
        # distance from the mate's axis (independent of the mate's turn): a window of the mover's angles
        d = np.hypot(*(np.einsum("ij,...j->...i", mt.R0.T, world(c3, coarse) - mt.origin)[..., :2].T))
        idx = np.flatnonzero((d >= band[0] - margin) & (d <= band[1] + margin))
        if not len(idx):
            continue
        lo, hi = coarse[max(idx.min() - 1, 0)], coarse[min(idx.max() + 1, len(coarse) - 1)]
        phis = np.linspace(lo, hi, 6001)
        w = world(c3, phis)
        for off in offsets:
            phi_mate = pair.ratio * phis + off if mover_is_1 else (phis - off) / pair.ratio
            R, _ = mt.rotation(phi_mate)
            loc = np.einsum("...ji,...j->...i", R, w - mt.origin)
            dep = mate.depth(loc[..., 0], loc[..., 1])
            k = int(np.argmax(dep))
            if dep[k] > worst:
                worst, where = float(dep[k]), float(phis[k])
    return worst, where


def _tip_depth(pair: GearPair, mover: Gear, a: float, j: float, aw: float) -> tuple[float, float]:
    """Largest depth [mm] of the tip corners of ``mover`` in its mate over the engagement (C5), and where."""
    flat = replace(pair, misalignment=Misalignment(), center_distance=a, mount1=None, mount2=None)
    rw2 = pair.gear2.r_b / math.cos(aw)
    half = 0.5 * max(j, 0.0) / rw2  # the driven gear's free turn to either flank
    o1, o2 = _outline(flat.gear1), _outline(flat.gear2)
    mv, mt = (o1, o2) if mover is pair.gear1 else (o2, o1)
    return _worst_penetration(mv, mt, flat, (-half, half))


def _fitting_addendum(pair: GearPair, g: Gear, a: float, j: float, aw: float) -> float | None:
    """The largest addendum h_a/m of gear g (bisection, 0.001) whose tip corners clear the mate (C5); None if none."""
    def depth(ha):
        try:
            h = replace(g, addendum=ha)
            p = replace(pair, gear1=h) if g is pair.gear1 else replace(pair, gear2=h)
            return _tip_depth(p, h, a, j, aw)[0] - PENETRATION_TOL * g.module
        except (InputError, GeometryError):
            return math.inf
    lo, hi = 0.05, g.addendum
    if depth(lo) > 0:
        return None
    while hi - lo > 1e-3:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if depth(mid) <= 0 else (lo, mid)
    return lo


def _check_tips(pair: GearPair, a: float, j: float, aw: float) -> None:
    """C4 and C5 (module docstring): no tip corner cuts into the mate, on or off the line of action."""
    for g, other in ((pair.gear1, pair.gear2), (pair.gear2, pair.gear1)):
        depth, phi = _tip_depth(pair, g, a, j, aw)
        if depth <= PENETRATION_TOL * other.module:
            continue
        below, r_meet = _tip_below_form(pair, a, aw, g)
        if below:
            what = (f"tip-fillet interference: the tip of {g.name} meets {other.name} at radius {r_meet:.4f} mm, "
                    f"beyond the start of its fillet (form circle {_form(other):.4f} mm), and cuts {depth:.4f} mm into it")
        else:
            what = (f"trochoid interference: a tip corner of {g.name} cuts {depth:.4f} mm into the teeth of {other.name} "
                    f"off the line of action as the teeth {'enter' if phi < 0 else 'leave'} the mesh")
        fit = _fitting_addendum(pair, g, a, j, aw)
        valid = (f"<= {fit:.3f} (tip shortening)" if fit is not None else
                 "a shorter tip, more teeth on the internal gear or other profile shifts")
        raise InputError(_key(g, "addendum"), g.addendum, valid, f"{what}, at the centre distance {a:.4f} mm")


def check_pair(pair: GearPair) -> PairGeometry:
    """Every check of the module docstring, in order; the first that fails raises InputError naming the key.

    Keys are named as in a case file relative to the gear tables (``<gear>.module_mm``) and the pair
    (``center_distance_mm``, ``misalignment.d_center_um``); a reader prefixes its table path. Results
    of pairs without explicit mounts are remembered (a sweep checks the same pair at every grid point).
    """
    if pair.mount1 is None:
        return _checked(pair.gear1, pair.gear2, pair.misalignment, pair.center_distance, pair.side1, pair.side2)
    return _check(pair)


@functools.lru_cache(maxsize=256)
def _checked(g1, g2, mis, cd, side1, side2) -> PairGeometry:
    return _check(GearPair(g1, g2, mis, center_distance=cd, side1=side1, side2=side2))


def _check(pair: GearPair) -> PairGeometry:
    g1, g2 = pair.gear1, pair.gear2
    check_meshing(g1, g2)
    a0 = standard_center_distance(g1, g2)
    azb = pair.zero_backlash_center_distance
    if pair.center_distance is not None:
        source = "given"
    else:
        source = "standard" if azb == a0 else "zero backlash"
        if not math.isfinite(azb):
            # (I3) of tca.geometry.involute with alpha_w -> 0: the largest (internal) or smallest (external) shift sum
            at = g1.transverse_pressure_angle
            z_int = g1.teeth if g1.internal else g2.teeth
            z_ext = g2.teeth if g1.internal else g1.teeth
            if pair.kind != "external":
                bound = f"<= {inv(at) * (z_int - z_ext) / (2 * math.tan(g1.pressure_angle)):.4f}"
            else:
                bound = f">= {-inv(at) * (g1.teeth + g2.teeth) / (2 * math.tan(g1.pressure_angle)):.4f}"
            xs = g1.profile_shift + g2.profile_shift
            raise InputError(_key(g2, "profile_shift"), g2.profile_shift,
                             f"a profile shift sum x1 + x2 {bound} (inv alpha_w >= 0: some centre distance closes the "
                             f"backlash)", f"x1 + x2 = {xs:g}: the teeth overlap at every centre distance")
    m1, m2 = pair.mounts() if pair.mount1 is None else (pair.mount1, pair.mount2)
    a = float(np.hypot(*(m2.origin - m1.origin)[:2]))  # with the misalignment d_center
    cd_key = "center_distance_mm" if pair.center_distance is not None else "misalignment.d_center_um"
    aw = working_pressure_angle(g1, g2, a)
    if not math.isfinite(aw):
        raise InputError("center_distance_mm", pair.E, f"a centre distance near the zero-backlash one, {azb:.4f} mm",
                         "no working pressure angle (the base circles overlap or the line of action is parallel)")
    j = backlash(g1, g2, a)
    if j < -BACKLASH_TOL:
        side = "<=" if pair.kind != "external" else ">="  # an internal pair gains backlash as the centres close
        if pair.center_distance is not None:
            raise InputError("center_distance_mm", pair.center_distance,
                             f"{side} {azb:.4f} mm, the centre distance of zero backlash (profile shifts x = "
                             f"{g1.profile_shift:g}, {g2.profile_shift:g}; inv alpha_w)"
                             + ("" if pair.misalignment.d_center == 0 else " with misalignment.d_center_um"),
                             f"at {a:.4f} mm the teeth overlap: backlash {j:.4f} mm < 0")
        raise InputError("misalignment.d_center_um", pair.misalignment.d_center * 1e3,
                         f"{'<=' if pair.kind == 'internal' else '>='} 0 um (the pair runs at its zero-backlash centre "
                         f"distance {azb:.4f} mm; the mount of an internal pair moves the other way)",
                         f"at {a:.4f} mm the teeth overlap: backlash {j:.4f} mm < 0")
    c = _check_clearance(pair, a, cd_key)
    _check_tips(pair, a, j, aw)
    ea, eb = contact_ratios(pair, a, aw)
    warnings = []
    if ea + eb < 1.0:
        warnings.append(f"contact ratio eps_alpha + eps_beta = {ea:.3f} + {eb:.3f} < 1: between pairs of teeth the load "
                        "passes over the tips (edge contact); lengthen the addenda or reduce the centre distance")
    return PairGeometry(pair.E, source, a0, azb, aw, j, c, ea, eb, tuple(warnings))
