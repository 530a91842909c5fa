r"""Double-helical one-stage planetary train of Part 1: data, assembly conditions, Eq. (1.16).

Members (Fig. 1.1): sun 1, planets :math:`2_k^{(i)}` (shafts ``i = 1..n``, members ``k = a, b`` of
opposite hands on one shaft, a gap :math:`F` between them), ring 3, carrier c. The sun drives, the
ring is held and the carrier is driven (Eqs. 1.1–1.2):

.. math::
    \frac{\omega_c}{\omega_1} = \frac{N_1}{N_1 + N_3}, \qquad
    \frac{N_1 + N_3}{n} = a \in \mathbb{Z} \ \ (1.3), \qquad N_2 = \frac{N_3 - N_1}{2} \ \ (1.4).

The gears given are the members *a*; members *b* are their mirror images (hand reversed).
Sun, planet and ring share the transverse geometry of the design helix (``reference_helix``,
Table 1.1: 10°) while their helix angles :math:`\beta_1 > \beta_2 > \beta_3` differ (section 1.3 (1)),
so the train assembles on the standard centre distance :math:`r_1 + r_2 = r_3 - r_2`.

Regulation of backlash (section 1.3): a member moved along its axis by :math:`\Delta Z` with the
screw motion of the ring keeps its contact with the ring while its backlash with the sun changes
by :math:`\Delta Z(\tan\beta_1 - \tan\beta_3)` on the pitch circle; an installment error
:math:`\Delta E_x` of the shaft (tangential on the carrier) changes it by :math:`2\Delta E_x` (the
planet turns to keep the ring contact). Equating both gives Eq. (1.16),

.. math:: \Delta E_x = \frac{\Delta Z^{(1)}\sin(\beta_1 - \beta_3)}{2\cos\beta_1\cos\beta_3}.

Sign conventions (the report gives none; these reproduce the signs of Table 1.2 and Fig. 1.4(a)):
:math:`\Delta E_x > 0` displaces the shaft *against* the sun's sense of rotation, which advances
that planet (it engages first); :math:`\Delta Z > 0` moves member *k* along
:math:`\sigma_{1k} z_f` (:math:`\sigma_{1k} = +1` for the right-hand sun member), which also
advances it, so :math:`\Delta Z^{(1)} = -2\Delta E_x\cos\beta_1\cos\beta_3/\sin(\beta_1-\beta_3)`
(−4.44 mm for +20 μm). Mirror-symmetric regulation of both members has equal ΔZ.
:math:`\Delta\gamma > 0` turns the shaft about the radial line through its centre (right-hand
rule about :math:`e_r`): member centres at :math:`\pm z_m` move tangentially by
:math:`\mp z_m\Delta\gamma`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property

from tca.errors import GeometryError, InputError
from tca.geometry.gear import Gear

__all__ = ["DoubleHelicalTrain", "ShaftErrors", "MEMBERS", "dz_first_order"]

MEMBERS = ("a", "b")


@dataclass(frozen=True)
class ShaftErrors:
    """Installment errors of one planet shaft: ΔE_x [mm] (tangential), Δγ [rad] (about e_r)."""

    d_ex: float = 0.0
    d_gamma: float = 0.0

    def __post_init__(self):
        if not abs(self.d_ex) <= 1.0:
            raise InputError("d_ex_um", self.d_ex * 1e3, "|value| <= 1000 um")
        if not abs(self.d_gamma) <= math.radians(1.0):
            raise InputError("d_gamma_arcmin", math.degrees(self.d_gamma) * 60, "|value| <= 60 arcmin")


@dataclass(frozen=True)
class DoubleHelicalTrain:
    """Sun, planet and ring members *a* (members *b* mirrored), n planet shafts, gap F [mm]."""

    sun: Gear
    planet: Gear
    ring: Gear
    planets: int  # n, number of planet shafts
    gap: float  # F, distance between the members a and b [mm]

    def __post_init__(self):
        s, p, r, n = self.sun, self.planet, self.ring, self.planets
        if not isinstance(n, int) or isinstance(n, bool) or not 1 <= n <= 20:
            raise InputError("planets", n, "an integer in [1, 20]")
        if not (0 <= self.gap <= 1000):
            raise InputError("member_gap_mm", self.gap, "in [0, 1000] mm")
        if s.internal or p.internal:
            g = s if s.internal else p
            raise InputError(f"gears.{g.name}.internal", True, "false (only the ring is internal)")
        if not r.internal:
            raise InputError(f"gears.{r.name}.internal", False, "true (the ring is an internal gear)")
        if (s.teeth + r.teeth) % n:
            raise InputError(f"gears.{r.name}.teeth", r.teeth,
                             f"N1 + N3 divisible by the number of planets n = {n} (Eq. 1.3): "
                             f"({s.teeth} + {r.teeth}) / {n} = {(s.teeth + r.teeth) / n:g} is not an integer")
        if 2 * p.teeth != r.teeth - s.teeth:
            raise InputError(f"gears.{p.name}.teeth", p.teeth,
                             f"(N3 - N1) / 2 = ({r.teeth} - {s.teeth}) / 2 = {(r.teeth - s.teeth) / 2:g} (Eq. 1.4)")
        for g in (p, r):
            for key, a, b in (("module_mm", g.module, s.module),
                              ("pressure_angle_deg", math.degrees(g.pressure_angle), math.degrees(s.pressure_angle)),
                              ("reference_helix_deg", math.degrees(g.beta_ref), math.degrees(s.beta_ref))):
                if abs(a - b) > 1e-12 * max(1.0, abs(b)):
                    raise InputError(f"gears.{g.name}.{key}", a, f"{b:g}, as the sun (the members of a planetary train "
                                     "share their transverse geometry; helix angles may differ)")
        if s.helix > 0 or p.helix > 0 or r.helix > 0:
            if p.hand == s.hand:
                raise InputError(f"gears.{p.name}.hand", _hand(p.hand), f"{_hand(-s.hand)} (opposite to the sun)")
            if r.hand != p.hand:
                raise InputError(f"gears.{r.name}.hand", _hand(r.hand), f"{_hand(p.hand)} (same hand as the planet)")
        # neighbouring planets must not overlap (tip circles apart on the carrier)
        chord = 2 * self.center_distance * math.sin(math.pi / n) if n > 1 else math.inf
        if chord <= 2 * p.r_tip:
            raise GeometryError(p.name, "planets overlap",
                                f"{n} planets on the centre distance {self.center_distance:.3f} mm are {chord:.3f} mm "
                                f"apart, less than the tip diameter {2 * p.r_tip:.3f} mm; use fewer planets")

    # ------------------------------------------------------------------ kinematics
    @property
    def a(self) -> int:
        """Integer a of Eq. (1.3)."""
        return (self.sun.teeth + self.ring.teeth) // self.planets

    @property
    def carrier_ratio(self) -> float:
        """omega_c / omega_1 = N1 / (N1 + N3), Eq. (1.2)."""
        return self.sun.teeth / (self.sun.teeth + self.ring.teeth)

    @property
    def inverted_ratio(self) -> float:
        """|omega_3 / omega_1| with the carrier at rest, N1 / N3 (Eq. 1.1)."""
        return self.sun.teeth / self.ring.teeth

    @property
    def center_distance(self) -> float:
        """Sun–planet centre distance r1 + r2 (= r3 - r2) [mm]."""
        return self.sun.r_p + self.planet.r_p

    @property
    def member_offset(self) -> float:
        """Axial position z_m = (F + B)/2 of the member centres [mm]."""
        return 0.5 * (self.gap + self.planet.face_width)

    def carrier_angle(self, i: int) -> float:
        """Angular position of shaft i (0-based) on the carrier, 2 pi i / n [rad]."""
        return 2 * math.pi * i / self.planets

    # ------------------------------------------------------------------ members
    @cached_property
    def _members_b(self) -> tuple[Gear, Gear, Gear]:
        return tuple(replace(g, hand=-g.hand, name=f"{g.name}_b") for g in (self.sun, self.planet, self.ring))

    def gears(self, member: str) -> tuple[Gear, Gear, Gear]:
        """(sun, planet, ring) of member 'a' (as given) or 'b' (mirror images)."""
        if member == "a":
            return self.sun, self.planet, self.ring
        if member == "b":
            return self._members_b
        raise InputError("member", member, "'a' or 'b'")

    def member_sign(self, member: str) -> int:
        """+1 for the member at z_f = +z_m (a), -1 for b."""
        return 1 if member == "a" else -1

    def dz_direction(self, member: str) -> int:
        """Sign s such that ΔZ > 0 moves the member along s z_f (the hand of its sun member)."""
        return self.gears(member)[0].hand


def dz_first_order(train: DoubleHelicalTrain, d_ex: float) -> float:
    """ΔZ^(1) [mm] compensating ΔE_x [mm] by Eq. (1.16), in the sign convention of the module."""
    b1, b3 = train.sun.helix, train.ring.helix
    if abs(b1 - b3) < 1e-9:
        raise InputError(f"gears.{train.ring.name}.helix_deg", math.degrees(b3),
                         f"different from the sun's {math.degrees(b1):g} deg: regulation needs beta1 != beta3 "
                         "(section 1.3 (1), Eq. 1.16)")
    return -2.0 * d_ex * math.cos(b1) * math.cos(b3) / math.sin(b1 - b3) + 0.0  # no -0.0


def _hand(h: int) -> str:
    return "right" if h > 0 else "left"
