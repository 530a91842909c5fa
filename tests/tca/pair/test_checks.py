"""The pair checks before any work (tca.pair.checks, issue 24 item 1), against closed forms of involute gearing.

The operating centre distance of zero backlash is recomputed here from the textbook relations
(inv alpha_w = 2 tan alpha (x1 + x2) / (z1 + z2) + inv alpha, a_w = a cos alpha / cos alpha_w, solved by
brentq), and the transverse contact ratio of an unshifted spur pair from
eps_alpha = (sqrt(r_a1^2 - r_b1^2) + sqrt(r_a2^2 - r_b2^2) - a sin alpha) / (pi m cos alpha): neither goes
through tca.geometry.involute.
"""

import math

import pytest
from scipy.optimize import brentq

from tca.errors import InputError
from tca.geometry.gear import Gear
from tca.pair.checks import check_pair
from tca.pair.gear_pair import GearPair

d = math.radians


def inv(a):
    return math.tan(a) - a


def spur(name, z, m=5.0, alpha=20.0, x=0.0, **kw):
    return Gear(name, z, m, d(alpha), 30.0, profile_shift=x, **kw)


def test_module_mismatch_refused_naming_the_module():
    with pytest.raises(InputError) as e:
        check_pair(GearPair(spur("p", 20, 5.0), spur("w", 52, 4.5)))
    assert e.value.field == "w.module_mm" and e.value.value == 4.5 and "cannot mesh" in str(e.value)
    with pytest.raises(InputError) as e:
        check_pair(GearPair(spur("p", 20, 4.5), spur("w", 52, 4.0)))
    assert e.value.field == "w.module_mm"


def test_pressure_angle_mismatch_refused():
    with pytest.raises(InputError) as e:
        check_pair(GearPair(spur("p", 20), spur("w", 52, alpha=25.0)))
    assert e.value.field == "w.pressure_angle_deg" and "20 deg" in str(e.value)


def test_equal_hands_refused_on_an_external_helical_pair():
    g1 = Gear("p", 17, 5.0, d(20), 30.0, helix=d(25), hand=1)
    g2 = Gear("w", 52, 5.0, d(20), 30.0, helix=d(25), hand=1)
    with pytest.raises(InputError) as e:
        check_pair(GearPair(g1, g2))
    assert e.value.field.endswith("hand")


def test_shifted_pair_runs_at_its_zero_backlash_centre_distance():
    z1, z2, x1, x2, m, al = 17, 52, 0.3, 0.3, 5.0, d(20)
    aw = brentq(lambda a: inv(a) - (2 * math.tan(al) * (x1 + x2) / (z1 + z2) + inv(al)), 0.1, 1.2)
    a_w = 0.5 * m * (z1 + z2) * math.cos(al) / math.cos(aw)
    geo = check_pair(GearPair(spur("p", z1, x=x1), spur("w", z2, x=x2)))
    assert geo.source == "zero backlash"
    assert geo.center_distance == pytest.approx(a_w, abs=1e-9)  # closed form solved to brentq's 1e-12 rad
    assert geo.working_pressure_angle == pytest.approx(aw, abs=1e-10)
    assert abs(geo.backlash) < 1e-9


@pytest.mark.parametrize("z1,x1,x2,cd", [(17, 0.3, 0.3, 172.5), (12, 0.5, 0.0, 160.0)])
def test_shifted_pair_at_the_standard_centre_distance_refused_naming_the_fitting_value(z1, x1, x2, cd):
    # the pairs: 17/52 with x = +0.3 on both gears, a 12-tooth pinion with x = +0.5, at a = m (z1 + z2) / 2
    with pytest.raises(InputError) as e:
        check_pair(GearPair(spur("p", z1, x=x1), spur("w", 52, x=x2), center_distance=cd))
    assert e.value.field == "center_distance_mm" and e.value.value == cd
    fit = check_pair(GearPair(spur("p", z1, x=x1), spur("w", 52, x=x2))).center_distance
    assert f"{fit:.4f}" in str(e.value) and "backlash" in str(e.value)


def test_unshifted_spur_pair_contact_ratio_matches_the_closed_form():
    z1, z2, m, al = 19, 24, 4.5, d(20)
    geo = check_pair(GearPair(spur("p", z1, m), spur("w", z2, m)))
    a = 0.5 * m * (z1 + z2)
    rb1, rb2 = 0.5 * m * z1 * math.cos(al), 0.5 * m * z2 * math.cos(al)
    ra1, ra2 = 0.5 * m * z1 + m, 0.5 * m * z2 + m
    ea = (math.sqrt(ra1**2 - rb1**2) + math.sqrt(ra2**2 - rb2**2) - a * math.sin(al)) / (math.pi * m * math.cos(al))
    assert geo.source == "standard" and geo.center_distance == pytest.approx(a, rel=1e-12)
    # the path is clipped to the form circles; for 19/24 teeth the tips limit it (no clipping): exact
    assert geo.transverse_contact_ratio == pytest.approx(ea, rel=1e-6)
    assert geo.overlap_ratio == 0.0 and not geo.warnings


def test_report_screw_parameters_stay_valid():
    # Part 1's regulated train: sun 10.25 deg, planet 10 deg, ring 9.75 deg on a common 10-degree rack
    sun = Gear("sun", 41, 2.0, d(20), 30.0, helix=d(10.25), hand=1, reference_helix=d(10))
    planet = Gear("planet", 34, 2.0, d(20), 30.0, helix=d(10), hand=-1)
    check_pair(GearPair(sun, planet))


def test_short_addenda_warn_below_contact_ratio_one():
    geo = check_pair(GearPair(spur("p", 30, 2.0, addendum=0.45), spur("w", 45, 2.0, addendum=0.45)))
    assert geo.contact_ratio < 1 and any("contact ratio" in w for w in geo.warnings)
