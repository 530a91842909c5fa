"""Planetary train data (Part 1): Eqs. (1.2)-(1.4) with clear errors, Eq. (1.16) against Table 1.2."""

import dataclasses
import math

import pytest

from tca.errors import GeometryError, InputError
from tca.planetary.train import DoubleHelicalTrain, ShaftErrors, dz_first_order
from tca.report_data import TABLE_1_1_MEMBER_GAP, TABLE_1_1_PLANETS, table_1_1_gears

d = math.radians


def table11(n_planet=34, beta1=10.25, beta3=9.75, planets=5, module_ring=2.0):
    """The Table 1.1 train with one datum changed (planet teeth, helices, planet count, ring module)."""
    sun, planet, ring = table_1_1_gears(beta_sun_deg=beta1, beta_ring_deg=beta3)
    planet = dataclasses.replace(planet, teeth=n_planet)
    ring = dataclasses.replace(ring, module=module_ring)
    return DoubleHelicalTrain(sun, planet, ring, planets, TABLE_1_1_MEMBER_GAP)


def test_table_1_1_train_ratios():
    t = table11()
    assert t.a == 30  # (41 + 109) / 5, Eq. (1.3)
    assert t.carrier_ratio == pytest.approx(41 / 150, rel=1e-15)  # Eq. (1.2)
    assert t.inverted_ratio == pytest.approx(41 / 109, rel=1e-15)
    # standard centre distances agree: r1 + r2 = r3 - r2 (shared transverse geometry, Eq. 1.4)
    assert t.center_distance == pytest.approx(t.ring.r_p - t.planet.r_p, abs=1e-12)
    assert t.member_offset == 20.0  # (F + B) / 2
    # members b are mirror images: opposite hands, same data otherwise
    sb, pb, rb = t.gears("b")
    assert (sb.hand, pb.hand, rb.hand) == (-1, 1, 1)
    assert pb.plunge == t.planet.plunge and rb.helix == t.ring.helix


def test_eq_1_3_violation_names_the_ring_and_the_sum():
    with pytest.raises(InputError, match=r"gears\.ring\.teeth.*divisible by the number of planets n = 4 \(Eq\. 1\.3\)"):
        table11(planets=4)  # 150 / 4 = 37.5


def test_eq_1_4_violation_names_the_planet():
    with pytest.raises(InputError, match=r"gears\.planet\.teeth = 33.*\(109 - 41\) / 2 = 34 \(Eq\. 1\.4\)"):
        table11(n_planet=33)


def test_transverse_geometry_must_be_shared():
    with pytest.raises(InputError, match=r"gears\.ring\.module_mm"):
        table11(module_ring=2.5)


def test_hands_of_the_members():
    sun, planet, ring = table_1_1_gears(beta_sun_deg=10.0, beta_ring_deg=10.0, crowned=False)
    planet = dataclasses.replace(planet, hand=1)  # the sun's hand: rejected
    with pytest.raises(InputError, match=r"gears\.planet\.hand.*left \(opposite to the sun\)"):
        DoubleHelicalTrain(sun, planet, ring, TABLE_1_1_PLANETS, TABLE_1_1_MEMBER_GAP)


def test_planets_that_overlap_are_rejected():
    # n = 10 satisfies Eq. (1.3) (150 / 10 = 15) but planets 47 mm apart cannot carry tip diameters of 73 mm
    with pytest.raises(GeometryError, match="planets overlap"):
        table11(planets=10)


@pytest.mark.parametrize("d_ex_um,report", [(20, -4.44), (-20, 4.44), (5, -1.11), (-5, 1.11), (0, 0.0)])
def test_eq_1_16_reproduces_table_1_2(d_ex_um, report):
    # Table 1.2, Delta Z^(1) "from Eq. (16)", to 0.01 mm (issue 3). Eq. (1.16) gives 4.4454 and 1.1114 mm:
    # the report prints them truncated to two decimals (4.44, 1.11), which we check too.
    dz = dz_first_order(table11(), d_ex_um * 1e-3)
    assert dz == pytest.approx(report, abs=0.01)
    assert math.trunc(dz * 100) / 100 == pytest.approx(report, abs=1e-12)
    # and Eq. (1.16) itself, exactly: Delta E_x = -Delta Z sin(b1 - b3) / (2 cos b1 cos b3) in our signs
    b1, b3 = d(10.25), d(9.75)
    assert -dz * math.sin(b1 - b3) / (2 * math.cos(b1) * math.cos(b3)) == pytest.approx(d_ex_um * 1e-3, abs=1e-15)


def test_eq_1_16_needs_different_helix_angles():
    with pytest.raises(InputError, match=r"beta1 != beta3"):
        dz_first_order(table11(beta1=10.0, beta3=10.0), 0.02)


def test_shaft_errors_range():
    with pytest.raises(InputError, match="d_ex_um"):
        ShaftErrors(d_ex=2.0)
    with pytest.raises(InputError, match="d_gamma_arcmin"):
        ShaftErrors(d_gamma=d(2))
