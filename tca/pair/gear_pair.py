r"""A gear pair in the fixed frame: mounts, misalignments, the flanks in contact.

Fixed frame :math:`S_f`: gear 1 turns about the z axis through O, its reference tooth centred on
+x at :math:`\phi_1 = 0`. Gear 2 sits on the x axis, at distance E:

* external pair: centre (E, 0, 0), frame turned by π about y (its z axis is −z_f, so it too turns
  positively while turning opposite to gear 1), a tooth space centred on the line of centres;
* internal gear 2 (a ring around gear 1): centre (−E, 0, 0), same z axis as gear 1;
* internal gear 1 (a ring driving gear 2 inside it): gear 2 centre (E, 0, 0), same z axis.

In this symmetric reference configuration, ideal gears with zero backlash have
:math:`\phi_2 = (N_1/N_2)\phi_1` exactly, so Eq. (1.13) measures the *absolute* transmission
error :math:`\Delta\phi_2 = \phi_2 - (N_1/N_2)\phi_1` (negative: the driven gear lags, e.g. by the
backlash created by crowning).

Misalignments (applied to gear 2): ``d_gamma`` — change of shaft angle, gear 2's axis turned about
the line of centres (axes become crossed); ``d_gamma_v`` — turned about the axis perpendicular to
the line of centres and to the gear axis (axes intersect); ``d_center`` ΔE — increase of the
centre distance; ``d_ex`` ΔE_x — displacement perpendicular to the shortest centre distance
(the installment error of Table 1.2); ``d_axial`` — displacement along gear 2's axis.

Multi-body trains (the planetary train of Part 1) may instead give both mounts explicitly
(``mount1``, ``mount2``, e.g. a planet whose shaft is displaced and tilted): they must stay close
to the reference configuration above, whose phases and angles the TCA uses for its start and
for Eq. (1.13); ``misalignment`` must then be left at zero.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from tca.contact.systems import PlacedFlank
from tca.errors import GeometryError, InputError
from tca.geometry.gear import Gear
from tca.geometry.involute import zero_backlash_center_distance
from tca.numerics.transforms import Mount, rot_x, rot_y

__all__ = ["Misalignment", "GearPair"]


@dataclass(frozen=True)
class Misalignment:
    """Errors of alignment of gear 2 [rad, mm]."""

    d_gamma: float = 0.0
    d_gamma_v: float = 0.0
    d_center: float = 0.0
    d_ex: float = 0.0
    d_axial: float = 0.0

    def __post_init__(self):
        for name in ("d_gamma", "d_gamma_v"):
            v = getattr(self, name)
            if not abs(v) <= math.radians(2):
                raise InputError(f"misalignment.{name}_arcmin", math.degrees(v) * 60, "|value| <= 120 arcmin")
        for name in ("d_center", "d_ex", "d_axial"):
            v = getattr(self, name)
            if not abs(v) <= 10:
                raise InputError(f"misalignment.{name}_mm", v, "|value| <= 10 mm")


@dataclass(frozen=True)
class GearPair:
    """Gear 1 drives gear 2 with flank `side1` (default the +y, driving flank) against `side2`."""

    gear1: Gear
    gear2: Gear
    misalignment: Misalignment = field(default_factory=Misalignment)
    center_distance: float | None = None  # default: zero backlash from the profile shifts (tca.geometry.involute) [mm]
    side1: int = 1
    side2: int = -1
    mount1: Mount | None = None  # explicit mounts (both or none), replacing the reference ones
    mount2: Mount | None = None

    def __post_init__(self):
        if (self.mount1 is None) != (self.mount2 is None):
            raise InputError("mount2" if self.mount2 is None else "mount1", None, "both explicit mounts or none")
        if self.mount1 is not None and self.misalignment != Misalignment():
            raise InputError("misalignment", self.misalignment, "zero when explicit mounts are given (apply the "
                             "errors to the mounts)")
        if self.gear1.internal and self.gear2.internal:
            raise InputError("gear2.internal", True, "at most one internal gear in a pair")
        if self.side1 not in (1, -1) or self.side2 not in (1, -1):
            raise InputError("side", (self.side1, self.side2), "+1 or -1")
        if self.center_distance is not None and not self.center_distance > 0:
            raise InputError("center_distance_mm", self.center_distance, "> 0")
        # helical pairs: hands must be opposite for external, equal for internal meshes
        g1, g2 = self.gear1, self.gear2
        if g1.helix > 0 and g2.helix > 0:
            same = g1.hand == g2.hand
            internal = g1.internal or g2.internal
            if internal != same:
                need = "the same hand (internal mesh)" if internal else "opposite hands (external mesh)"
                raise InputError(f"{g2.name}.hand", "right" if g2.hand > 0 else "left", need)
        if (g1.internal or g2.internal):
            ext, intl = (g2, g1) if g1.internal else (g1, g2)
            if intl.teeth - ext.teeth < 5:
                raise InputError(f"{intl.name}.teeth", intl.teeth, f">= {ext.teeth + 5} (internal gear must have more teeth than its pinion)")
            margin = self.trochoid_margin()
            if margin < 0:
                raise GeometryError(
                    "pair", "tip clash",
                    f"the tips of {ext.name} ({ext.teeth} teeth) and of the internal gear {intl.name} ({intl.teeth} teeth) "
                    f"clash as the teeth leave the mesh (trochoid interference, margin {margin:.2e} rad < 0); "
                    f"use more teeth on {intl.name} or shorter addenda")

    def trochoid_margin(self) -> float:
        r"""Trochoid-interference margin of an internal pair [rad]: >= 0 when the tips pass free.

        As the pinion (1) tooth leaves the mesh its tip corner runs along a trochoid relative to the
        internal gear (2); it clears the internal gear's tip corner when (transverse plane, centre
        distance :math:`a`, working pressure angle :math:`\alpha_w`, tip pressure angles
        :math:`\alpha_{ai} = \arccos(r_{bi}/r_{ai})`)

        .. math::
            \frac{z_1}{z_2}\theta_1 + \mathrm{inv}\,\alpha_w - \mathrm{inv}\,\alpha_{a2} - \theta_2 \ge 0,\quad
            \theta_1 = \arccos\frac{r_{a2}^2 - r_{a1}^2 - a^2}{2 a r_{a1}} + \mathrm{inv}\,\alpha_{a1}
            - \mathrm{inv}\,\alpha_w,\quad
            \theta_2 = \arccos\frac{a^2 + r_{a2}^2 - r_{a1}^2}{2 a r_{a2}}

        (the angles turned by each gear from the tips' crossing point to the end of the path of
        contact; e.g. a standard 20 deg spur pinion of 34 teeth needs a ring of 43 or more). External pairs: +inf.
        """
        if self.kind == "external":
            return math.inf
        ext, intl = (self.gear2, self.gear1) if self.gear1.internal else (self.gear1, self.gear2)
        inv = lambda x: math.tan(x) - x  # noqa: E731
        a = self.E
        a0 = intl.r_p - ext.r_p
        c = a0 * math.cos(ext.transverse_pressure_angle) / a
        if not -1.0 < c < 1.0:
            return math.inf  # no working pressure angle: other checks report the centre distance
        aw = math.acos(c)
        ra1, ra2 = ext.r_tip, intl.r_tip
        c1 = (ra2**2 - ra1**2 - a**2) / (2 * a * ra1)
        c2 = (a**2 + ra2**2 - ra1**2) / (2 * a * ra2)
        if not (-1.0 <= c1 <= 1.0 and -1.0 <= c2 <= 1.0):
            return math.inf  # the tip circles do not cross: no trochoid reaches the internal gear's tips
        t1 = math.acos(c1) + inv(math.acos(ext.r_b / ra1)) - inv(aw)
        t2 = math.acos(c2)
        return ext.teeth / intl.teeth * t1 + inv(aw) - inv(math.acos(intl.r_b / ra2)) - t2

    @property
    def kind(self) -> str:
        if self.gear2.internal:
            return "internal"
        if self.gear1.internal:
            return "internal-driver"
        return "external"

    @property
    def standard_center_distance(self) -> float:
        r1, r2 = self.gear1.r_p, self.gear2.r_p
        return r1 + r2 if self.kind == "external" else abs(r2 - r1)

    @property
    def zero_backlash_center_distance(self) -> float:
        """Operating centre distance of zero backlash from the profile shifts, inv alpha_w [mm]
        (:func:`tca.geometry.involute.zero_backlash_center_distance`; the standard one without shifts)."""
        return zero_backlash_center_distance(self.gear1, self.gear2)

    @property
    def E(self) -> float:
        """Nominal centre distance [mm] (before misalignment): the given one, or the zero-backlash one."""
        return self.zero_backlash_center_distance if self.center_distance is None else self.center_distance

    @property
    def ratio(self) -> float:
        """Nominal ratio N1/N2 (dphi2/dphi1)."""
        return self.gear1.teeth / self.gear2.teeth

    def mounts(self) -> tuple[Mount, Mount]:
        """Mounts of gear 1 and (misaligned) gear 2 in S_f (the explicit ones when given)."""
        if self.mount1 is not None:
            return self.mount1, self.mount2
        m1 = Mount(np.zeros(3), np.eye(3), 0.0)
        E = self.E
        ms = self.misalignment
        ph2 = math.pi / self.gear2.teeth  # tooth space of gear 2 on the line of centres
        if self.kind == "external":
            m2 = Mount(np.array([E + ms.d_center, 0, 0]), rot_y(math.pi), ph2)
        elif self.kind == "internal":
            m2 = Mount(np.array([-(E + ms.d_center), 0, 0]), np.eye(3), ph2)
        else:
            m2 = Mount(np.array([E - ms.d_center, 0, 0]), np.eye(3), ph2)
        c = m2.origin.copy()
        R = rot_x(ms.d_gamma) @ rot_y(ms.d_gamma_v)
        m2 = Mount(c, R @ m2.R0, ph2)  # turned about axes through gear 2's centre
        m2 = Mount(m2.origin + np.array([0.0, ms.d_ex, 0.0]) + ms.d_axial * m2.R0[:, 2], m2.R0, ph2)
        return m1, m2

    def flanks(self) -> tuple[PlacedFlank, PlacedFlank]:
        """(flank 1, flank 2) in contact, reference teeth, placed by :meth:`mounts`."""
        m1, m2 = self.mounts()
        return PlacedFlank(self.gear1, self.side1, m1), PlacedFlank(self.gear2, self.side2, m2)

    def with_misalignment(self, **kw) -> "GearPair":
        """Copy with some misalignment components replaced."""
        from dataclasses import replace

        return replace(self, misalignment=replace(self.misalignment, **kw))
