r"""Gear data of the report's numerical examples (NASA/CR-2005-214002), written once.

Table 1.1 (Part 1, Numerical Examples 1.1-1.3): double-helical planetary train, sun 1 / planet 2 / ring 3 with
41 / 34 / 109 teeth, normal module 2 mm, normal pressure angle 20 deg, face width 30 mm per member, five planet
shafts (Eq. 1.3: (41 + 109) / 5 = 30), member gap F = 10 mm. Helix angles regulated as
:math:`\beta_1 = 10.25^\circ, \beta_2 = 10^\circ, \beta_3 = 9.75^\circ` (section 1.5) on the transverse
geometry of the 10 deg design (``reference_helix``, section 1.3 (1)); the pair studies use the 10 deg design
helix on the sun too. New design: double-crowned planet (profile parabolas :math:`a_{cd} = 0.008`,
:math:`a_{cc} = 0.005` 1/mm, disk of radius 100 mm plunging on :math:`a_{pl} = 0.002` 1/mm, Eqs. 1.5-1.6) and
ring with profile crowning 0.002 1/mm on both flanks; the conventional design is involute throughout.
Members *a* are given (sun right-hand, planet and ring left-hand); members *b* are their mirror images.

Table 3.1 (Part 3, section 3.4): spur isostatic train, sun / planet / ring with 65 / 43 / 151 teeth, module 4 mm,
20 deg, face width 40 mm, three planets; the double-crowned planet has profile parabolas 1.25e-3 1/mm on both
flanks and a disk of radius 100 mm plunging on 6.25e-5 1/mm. Section 3.4.2's indexing error of the carrier is
:math:`\Delta E_t = 20\ \mu m` on planet 1.
"""

from __future__ import annotations

import math

from tca.geometry.modifications.crowning import DiskPlunge
from tca.geometry.gear import Gear
from tca.isostatic.train import PlanetPlacement
from tca.planetary.train import DoubleHelicalTrain

__all__ = [
    "TABLE_1_1_MEMBER_GAP", "TABLE_1_1_PLANETS", "indexing_error_placements", "table_1_1_gears", "table_1_1_planet",
    "table_1_1_ring", "table_1_1_sun", "table_1_1_train", "table_3_1_gears", "table_3_1_planet", "table_3_1_ring",
    "table_3_1_sun",
]

d = math.radians

TABLE_1_1_PLANETS = 5  # planet shafts n (Eq. 1.3)
TABLE_1_1_MEMBER_GAP = 10.0  # gap F between the members a and b [mm]
_DESIGN_HELIX_DEG = 10.0  # helix of the shared transverse geometry [deg]


def _reference_helix(beta_deg: float) -> float | None:
    """Reference helix [rad] of a Table 1.1 gear with helix beta_deg, None when it is the design helix."""
    return None if beta_deg == _DESIGN_HELIX_DEG else d(_DESIGN_HELIX_DEG)


def table_1_1_sun(beta_deg: float = 10.25) -> Gear:
    """Table 1.1 sun member a (41 teeth, right hand) with helix beta_deg [deg] on the 10 deg transverse geometry."""
    return Gear("sun", 41, 2.0, d(20), 30.0, helix=d(beta_deg), hand=1, reference_helix=_reference_helix(beta_deg))


def table_1_1_planet(crowned: bool = True) -> Gear:
    """Table 1.1 planet member a (34 teeth, left hand, 10 deg); double-crowned (a_cd, a_cc, disk) or involute."""
    if not crowned:
        return Gear("planet", 34, 2.0, d(20), 30.0, helix=d(10), hand=-1)
    return Gear("planet", 34, 2.0, d(20), 30.0, helix=d(10), hand=-1, parabola_pos=0.008, parabola_neg=0.005,
                plunge=DiskPlunge(100.0, 0.002))


def table_1_1_ring(beta_deg: float = 9.75, crowned: bool = True) -> Gear:
    """Table 1.1 ring member a (109 teeth, internal, left hand), helix beta_deg [deg]; profile-crowned 0.002 1/mm."""
    crowning = dict(parabola_pos=0.002, parabola_neg=0.002) if crowned else {}
    return Gear("ring", 109, 2.0, d(20), 30.0, helix=d(beta_deg), hand=-1, reference_helix=_reference_helix(beta_deg),
                internal=True, **crowning)


def table_1_1_gears(beta_sun_deg: float = 10.25, beta_ring_deg: float = 9.75,
                    crowned: bool = True) -> tuple[Gear, Gear, Gear]:
    """Table 1.1 (sun, planet, ring), members a; helices [deg]; new design (crowned) or conventional involute."""
    return table_1_1_sun(beta_sun_deg), table_1_1_planet(crowned), table_1_1_ring(beta_ring_deg, crowned)


def table_1_1_train(beta_sun_deg: float = 10.25, beta_ring_deg: float = 9.75, crowned: bool = True) -> DoubleHelicalTrain:
    """Table 1.1 double-helical train: 5 planet shafts, member gap 10 mm, helices [deg]."""
    return DoubleHelicalTrain(*table_1_1_gears(beta_sun_deg, beta_ring_deg, crowned), TABLE_1_1_PLANETS,
                              TABLE_1_1_MEMBER_GAP)


def table_3_1_sun(name: str = "sun") -> Gear:
    """Table 3.1 spur sun (65 teeth, module 4 mm, 20 deg, face 40 mm)."""
    return Gear(name, 65, 4.0, d(20), 40.0)


def table_3_1_planet(crowned: bool = False, name: str = "planet") -> Gear:
    """Table 3.1 spur planet (43 teeth): involute, or crowned 1.25e-3 1/mm both flanks + disk a_l 6.25e-5 1/mm."""
    if not crowned:
        return Gear(name, 43, 4.0, d(20), 40.0)
    return Gear(name, 43, 4.0, d(20), 40.0, parabola_pos=1.25e-3, parabola_neg=1.25e-3,
                plunge=DiskPlunge(100.0, 6.25e-5))


def table_3_1_ring(name: str = "ring") -> Gear:
    """Table 3.1 spur ring (151 teeth, internal)."""
    return Gear(name, 151, 4.0, d(20), 40.0, internal=True)


def table_3_1_gears(crowned: bool = False) -> tuple[Gear, Gear, Gear]:
    """Table 3.1 (sun, planet, ring); the planet involute or double-crowned."""
    return table_3_1_sun(), table_3_1_planet(crowned), table_3_1_ring()


def indexing_error_placements() -> tuple[PlanetPlacement, PlanetPlacement, PlanetPlacement]:
    """Section 3.4.2: carrier indexing error Delta E_t = 0.020 mm on planet 1, planets 2 and 3 exact."""
    return (PlanetPlacement(tangential=0.020), PlanetPlacement(), PlanetPlacement())
