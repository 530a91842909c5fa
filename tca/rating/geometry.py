r"""Pair geometry of cylindrical involute gears from basic data (ISO 21771, as used by ISO 6336-1).

Input: :class:`PairData` (normal module :math:`m_n`, normal pressure angle :math:`\alpha_n`, helix angle
:math:`\beta` at the reference circle, two :class:`GearBlank` records with :math:`z, x, b` and optional tip and
root diameters, optional centre distance :math:`a`, external or internal). Units: mm, rad.

Internal pairs are written here with magnitudes: :math:`z_2 > 0`, :math:`d_2 > 0`, :math:`a > 0`, and a sign
:math:`\kappa = +1` (external) or :math:`-1` (internal) where ISO 21771 writes signed :math:`z_2`. The wheel's
profile shift keeps the ISO 21771 sign convention, in which (G5) reads :math:`|d_{a2}| = d_2 - 2 m_n (h_{aP}^* + x_2)`
for an internal gear (a negative :math:`x_2` moves its tip circle outward, away from the axis).

.. math::
    m_t = \frac{m_n}{\cos\beta},\quad \tan\alpha_t = \frac{\tan\alpha_n}{\cos\beta},\quad
    \sin\beta_b = \sin\beta\cos\alpha_n \quad (G1)

    d = z m_t,\quad d_b = d\cos\alpha_t,\quad p_{bt} = \pi m_t \cos\alpha_t \quad (G2)

    a_0 = \tfrac12 (d_2 + \kappa d_1) \text{ (magnitude)},\qquad
    \operatorname{inv}\alpha_{wt} = \operatorname{inv}\alpha_t + 2\tan\alpha_n \frac{x_1 + x_2}{z_2 + \kappa z_1}\kappa
    \ \text{(from the shifts)},\qquad \cos\alpha_{wt} = \frac{a_0}{a}\cos\alpha_t \ \text{(from } a) \quad (G3)

    d_w = \frac{d_b}{\cos\alpha_{wt}},\qquad a = \frac{a_0 \cos\alpha_t}{\cos\alpha_{wt}} \quad (G4)

    d_{a1} = d_1 + 2 m_n (h_{aP}^* + x_1),\quad d_{f1} = d_1 - 2 m_n (h_{fP}^* - x_1);\qquad
    d_{a2} = d_2 + 2\kappa m_n (h_{aP}^* + x_2),\quad d_{f2} = d_2 - 2\kappa m_n (h_{fP}^* - x_2) \quad (G5)

(defaults only: given tip and root diameters, e.g. with tip shortening or generated with allowances, win),

.. math::
    g_\alpha = \tfrac12\sqrt{d_{a1}^2 - d_{b1}^2} + \kappa\left(\tfrac12\sqrt{d_{a2}^2 - d_{b2}^2} - a\sin\alpha_{wt}\right)
    \quad (G6)

    \varepsilon_\alpha = \frac{g_\alpha}{p_{bt}},\quad \varepsilon_\beta = \frac{b \sin\beta}{\pi m_n},\quad
    \varepsilon_\gamma = \varepsilon_\alpha + \varepsilon_\beta,\quad b = \min(b_1, b_2) \quad (G7)

    z_n = \frac{z}{\cos^2\beta_b\cos\beta},\qquad \varepsilon_{\alpha n} = \frac{\varepsilon_\alpha}{\cos^2\beta_b}
    \quad (G8)

    \rho_{1,2} = \tfrac12 d_{b1,2}\tan\alpha_{wt},\qquad \rho_{red} = \frac{\rho_1\rho_2}{\rho_2 + \kappa\rho_1}
    \quad \text{(transverse radii of curvature at the pitch point)} \quad (G9)

    h = \tfrac12 |d_a - d_f| \text{ (tooth depth)},\qquad d_m = \tfrac12 (d_a + d_f) \text{ (mean diameter)} \quad (G10)

(G1)-(G7) are ISO 21771 (2007) clauses 4 and 5 in the form ISO/TR 6336-30 uses them; (G8) is ISO 6336-3's
virtual gear; (G9) the pitch-point curvature of ISO 6336-2 (Z_R); (G10) the depth of ISO 6336-1 (N_F) and the mean
diameter of its reduced mass.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tca.rating.errors import RatingInputError, RatingWarning, check_range

__all__ = ["GearBlank", "PairData", "PairGeometry", "pair_geometry", "inv", "inv_inverse", "DEG"]

DEG = math.pi / 180.0  # one degree [rad]


def inv(alpha: float) -> float:
    """Involute function tan α - α."""
    return math.tan(alpha) - alpha


def inv_inverse(value: float) -> float:
    """The angle α in [0, π/2) with inv α = ``value`` (Newton from a cube-root start)."""
    if not value >= 0.0:
        raise RatingInputError("inv_alpha", value, ">= 0 (an involute angle)")
    if value == 0.0:
        return 0.0
    a = min((3.0 * value) ** (1.0 / 3.0), 1.4)
    for _ in range(60):
        t = math.tan(a)
        step = (t - a - value) / (t * t)  # d(inv)/dα = tan²α
        a -= step
        a = min(max(a, 1e-12), 1.5)
        if abs(step) < 1e-15:
            return a
    raise RatingInputError("inv_alpha", value, "an involute value reached by α < 86°")


@dataclass(frozen=True)
class GearBlank:
    """One gear's basic data [mm]: teeth, face width, profile shift (ISO 21771 sign), optional diameters.

    ``tip_diameter``/``root_diameter`` are magnitudes; left ``None`` they follow (G5). ``bore_diameter`` d_i is
    used by the reduced mass of ISO 6336-1 (0: solid).
    """

    teeth: int
    face_width: float
    profile_shift: float = 0.0
    tip_diameter: float | None = None
    root_diameter: float | None = None
    bore_diameter: float = 0.0

    def __post_init__(self):
        if isinstance(self.teeth, bool) or int(self.teeth) != self.teeth or not 5 <= int(self.teeth) <= 10000:
            raise RatingInputError("teeth", self.teeth, "an integer in [5, 10000]")
        object.__setattr__(self, "teeth", int(self.teeth))
        check_range("face_width", self.face_width, 0.0, lo_open=True)
        check_range("profile_shift", self.profile_shift, -3.0, 3.0)
        for key in ("tip_diameter", "root_diameter"):
            v = getattr(self, key)
            if v is not None:
                check_range(key, v, 0.0, lo_open=True)
        check_range("bore_diameter", self.bore_diameter, 0.0)


@dataclass(frozen=True)
class PairData:
    """Basic data of a pair [mm, rad]: pinion (gear 1, fewer teeth) and wheel (gear 2).

    ``addendum``/``dedendum``: basic rack h_aP/m_n and h_fP/m_n, used for the default diameters (G5) and for the
    stiffness factor C_B of ISO 6336-1. ``internal``: the wheel is an internal (ring) gear.
    """

    normal_module: float
    pressure_angle: float
    helix_angle: float
    pinion: GearBlank
    wheel: GearBlank
    centre_distance: float | None = None
    internal: bool = False
    addendum: float = 1.0
    dedendum: float = 1.25

    def __post_init__(self):
        check_range("normal_module", self.normal_module, 0.0, lo_open=True)
        check_range("pressure_angle_deg", self.pressure_angle / DEG, 10.0, 35.0)
        check_range("helix_angle_deg", self.helix_angle / DEG, 0.0, 45.0, hi_open=True,
                    why="use the magnitude of β; ISO 6336 is applied up to 30°, with a warning up to 45°")
        if not isinstance(self.pinion, GearBlank) or not isinstance(self.wheel, GearBlank):
            raise RatingInputError("pinion/wheel", (type(self.pinion).__name__, type(self.wheel).__name__), "GearBlank records")
        if self.pinion.teeth > self.wheel.teeth:
            raise RatingInputError("pinion.teeth", self.pinion.teeth,
                                   f"<= wheel.teeth = {self.wheel.teeth} (gear 1 is the pinion, the smaller gear)")
        if self.internal and self.wheel.teeth - self.pinion.teeth < 6:
            raise RatingInputError("wheel.teeth", self.wheel.teeth, f">= pinion.teeth + 6 = {self.pinion.teeth + 6} "
                                   "for an internal pair (tip interference)")
        if self.centre_distance is not None:
            check_range("centre_distance", self.centre_distance, 0.0, lo_open=True)
        check_range("addendum", self.addendum, 0.5, 1.5)
        check_range("dedendum", self.dedendum, 0.8, 2.0)


@dataclass(frozen=True)
class PairGeometry:
    """Derived geometry of a pair [mm, rad]; pairs of values are (pinion, wheel), diameters as magnitudes."""

    internal: bool
    normal_module: float
    transverse_module: float
    pressure_angle: float  # α_n
    transverse_pressure_angle: float  # α_t
    working_pressure_angle: float  # α_wt
    helix_angle: float  # β
    base_helix_angle: float  # β_b
    teeth: tuple[int, int]
    profile_shift: tuple[float, float]
    face_width: tuple[float, float]
    common_face_width: float  # b = min(b1, b2)
    gear_ratio: float  # u = z2/z1 (magnitude)
    centre_distance: float  # a (magnitude)
    reference_diameter: tuple[float, float]  # d
    base_diameter: tuple[float, float]  # d_b
    working_diameter: tuple[float, float]  # d_w
    tip_diameter: tuple[float, float]  # d_a
    root_diameter: tuple[float, float]  # d_f
    mean_diameter: tuple[float, float]  # d_m
    tooth_depth: tuple[float, float]  # h
    bore_diameter: tuple[float, float]  # d_i
    transverse_base_pitch: float  # p_bt
    path_of_contact: float  # g_α
    eps_alpha: float
    eps_beta: float
    eps_gamma: float
    eps_alpha_n: float
    virtual_teeth: tuple[float, float]  # z_n (wheel: magnitude; internal gears have infinite z_n in c', see stiffness)
    pitch_curvature: tuple[float, float]  # ρ at the pitch point (transverse)
    relative_curvature: float  # ρ_red (G9)
    tip_curvature: tuple[float, float]  # ½ sqrt(d_a² - d_b²): radius of curvature at the tip circles
    x_sum_from_centre_distance: float  # x1 + x2 implied by a (== given sum when a follows the shifts)
    addendum: float
    dedendum: float
    warnings: tuple[RatingWarning, ...]

    @property
    def kappa(self) -> int:
        """+1 external, -1 internal."""
        return -1 if self.internal else 1


def pair_geometry(data: PairData) -> PairGeometry:
    """Geometry (G1)-(G10) of ``data``; warnings for ε_α < 1, β > 30° and a centre distance off the shifts."""
    mn, an, beta = data.normal_module, data.pressure_angle, data.helix_angle
    g1, g2 = data.pinion, data.wheel
    k = -1 if data.internal else 1
    z1, z2 = g1.teeth, g2.teeth
    x1, x2 = g1.profile_shift, g2.profile_shift
    mt = mn / math.cos(beta)
    at = math.atan(math.tan(an) / math.cos(beta))
    bb = math.asin(math.sin(beta) * math.cos(an))
    d1, d2 = z1 * mt, z2 * mt
    db1, db2 = d1 * math.cos(at), d2 * math.cos(at)
    a0 = 0.5 * (d2 + k * d1)
    warnings: list[RatingWarning] = []

    # (G3) from the shifts; kappa * (x1 + x2) / (z2 + kappa z1) is ISO's (x1 + x2)/(z1 + z2) with signed z2
    inv_wt_shifts = inv(at) + 2.0 * math.tan(an) * k * (x1 + x2) / (z2 + k * z1)
    if data.centre_distance is None:
        if inv_wt_shifts <= 0.0:
            raise RatingInputError("profile_shift", (x1, x2), "shifts giving a positive working pressure angle")
        awt = inv_inverse(inv_wt_shifts)
        a = a0 * math.cos(at) / math.cos(awt)
    else:
        a = float(data.centre_distance)
        c = a0 * math.cos(at) / a
        if not 0.0 < c < 1.0:
            raise RatingInputError("centre_distance", a, f"> {a0 * math.cos(at):.4f} mm (a_0 cos α_t, Eq. G3)")
        awt = math.acos(c)
    x_sum_a = (inv(awt) - inv(at)) * (z2 + k * z1) / (2.0 * math.tan(an) * k)
    if data.centre_distance is not None and abs(x_sum_a - (x1 + x2)) > 0.05:
        warnings.append(RatingWarning(
            "centre_distance_vs_shifts",
            f"the centre distance a = {a:.4f} mm implies x1 + x2 = {x_sum_a:.4f}, the shifts sum to {x1 + x2:.4f}: "
            "α_wt follows a, the tooth forms follow the shifts"))

    ha, hf = data.addendum, data.dedendum
    da1 = g1.tip_diameter if g1.tip_diameter is not None else d1 + 2 * mn * (ha + x1)
    df1 = g1.root_diameter if g1.root_diameter is not None else d1 - 2 * mn * (hf - x1)
    da2 = g2.tip_diameter if g2.tip_diameter is not None else d2 + 2 * k * mn * (ha + x2)
    df2 = g2.root_diameter if g2.root_diameter is not None else d2 - 2 * k * mn * (hf - x2)
    if not da1 > db1:
        raise RatingInputError("pinion.tip_diameter", da1, f"> base diameter {db1:.4f} mm")
    if not da2 > db2:
        raise RatingInputError("wheel.tip_diameter", da2, f"> base diameter {db2:.4f} mm")
    if not df1 < da1 or not (df2 < da2 if k > 0 else df2 > da2):
        raise RatingInputError("root_diameter", (df1, df2), "below the tip circle (external), above it (internal)")

    ra1 = 0.5 * math.sqrt(da1 * da1 - db1 * db1)
    ra2 = 0.5 * math.sqrt(da2 * da2 - db2 * db2)
    g_alpha = ra1 + k * (ra2 - a * math.sin(awt))
    pbt = math.pi * mt * math.cos(at)
    if not g_alpha > 0.0:
        raise RatingInputError("tip_diameter", (da1, da2), "tip circles that give a path of contact > 0")
    eps_a = g_alpha / pbt
    b = min(g1.face_width, g2.face_width)
    eps_b = b * math.sin(beta) / (math.pi * mn)
    rho1, rho2 = 0.5 * db1 * math.tan(awt), 0.5 * db2 * math.tan(awt)
    rho_red = rho1 * rho2 / (rho2 + k * rho1)
    zn1 = z1 / (math.cos(bb) ** 2 * math.cos(beta))
    zn2 = z2 / (math.cos(bb) ** 2 * math.cos(beta))

    if eps_a < 1.0:
        warnings.append(RatingWarning(
            "eps_alpha_below_1", f"transverse contact ratio ε_α = {eps_a:.4f} < 1: ISO 6336 assumes ε_α >= 1 "
            "(continuous transverse contact); rated anyway"))
    if beta > 30.0 * DEG + 1e-12:
        warnings.append(RatingWarning(
            "helix_above_30deg", f"helix angle β = {beta / DEG:.3f}° > 30°: outside the range of ISO 6336's "
            "factors (Y_β takes β = 30°, its cap; the other factors are evaluated at β); rated anyway"))

    return PairGeometry(
        internal=data.internal, normal_module=mn, transverse_module=mt, pressure_angle=an,
        transverse_pressure_angle=at, working_pressure_angle=awt, helix_angle=beta, base_helix_angle=bb,
        teeth=(z1, z2), profile_shift=(x1, x2), face_width=(g1.face_width, g2.face_width), common_face_width=b,
        gear_ratio=z2 / z1, centre_distance=a, reference_diameter=(d1, d2), base_diameter=(db1, db2),
        working_diameter=(db1 / math.cos(awt), db2 / math.cos(awt)), tip_diameter=(da1, da2),
        root_diameter=(df1, df2), mean_diameter=(0.5 * (da1 + df1), 0.5 * (da2 + df2)),
        tooth_depth=(0.5 * abs(da1 - df1), 0.5 * abs(da2 - df2)), bore_diameter=(g1.bore_diameter, g2.bore_diameter),
        transverse_base_pitch=pbt, path_of_contact=g_alpha, eps_alpha=eps_a, eps_beta=eps_b,
        eps_gamma=eps_a + eps_b, eps_alpha_n=eps_a / math.cos(bb) ** 2, virtual_teeth=(zn1, zn2),
        pitch_curvature=(rho1, rho2), relative_curvature=rho_red, tip_curvature=(ra1, ra2),
        x_sum_from_centre_distance=x_sum_a, addendum=ha, dedendum=hf, warnings=tuple(warnings))
