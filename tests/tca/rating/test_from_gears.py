"""A gearfe pair rated by ISO 6336 (tca.rating.from_gears): geometry taken from the generated gears, torques and
speeds converted to the pinion, Y_F/Y_S of the generated teeth, σ_H0 against Hertz's closed form, warnings."""

import math
from dataclasses import replace

import pytest

from tca.geometry.gear import Gear
from tca.pair.gear_pair import GearPair, Misalignment
from tca.pair.te import path_of_contact
from tca.rating import Given, Source, iso_material, rate
from tca.rating.from_gears import (GearSpec, Load, Service, mesh_misalignment, nominal_contact, pair_data, pinion_first,
                                   rating_case)
from tca.rating.root_stress import root_factors, tooth_root
from tca.units import ARCMIN

EH = iso_material("Eh", "MQ", 700)
SPECS = {n: GearSpec(EH, 6) for n in ("pinion", "wheel")}
E, NU = 2.068e5, 0.29


def spur(**kw):
    g1 = Gear("pinion", 19, 4.5, math.radians(20), 14.0, **kw)
    g2 = Gear("wheel", 24, 4.5, math.radians(20), 14.0, **kw)
    return GearPair(g1, g2)


def test_pair_data_takes_the_generated_gears():
    pair = spur()
    d = pair_data(pair)
    assert d.pinion.teeth == 19 and d.wheel.teeth == 24
    assert d.pinion.tip_diameter == pytest.approx(2 * pair.gear1.r_tip)
    assert d.wheel.root_diameter == pytest.approx(2 * pair.gear2.r_root)
    assert d.centre_distance == pytest.approx(pair.E)
    # the pinion is the gear with fewer teeth, whichever drives
    rev = GearPair(pair.gear2, pair.gear1)
    assert [g.name for g in pinion_first(rev)] == ["pinion", "wheel"]


def test_root_factors_and_sigma_f0_agree_with_the_generated_tooth():
    pair = spur()
    rp = rating_case(pair, SPECS, Service(1000.0), Load(120e3))
    eps = path_of_contact(pair).contact_ratio
    rf = root_factors(pair.gear1, eps)
    assert rp.case.pinion.form_factor == pytest.approx(rf.y_f, rel=1e-3)  # ε_α of ISO's geometry vs the TCA's path
    assert rp.case.pinion.form_source is Source.GEARFE
    r = rate(rp.case)
    # σ_F0 of the rating equals gearfe's own ISO 6336-3 evaluation (tooth_root), the same torque on the wheel
    assert r.pinion.sigma_f0 == pytest.approx(tooth_root(pair, 120e3)["pinion"]["sigma_f0_mpa"], rel=1e-3)


def test_torque_and_speed_given_on_either_gear_are_the_same_rating():
    pair = spur()
    a = rate(rating_case(pair, SPECS, Service(1000.0, "driver"), Load(120e3, "driven")).case)
    b = rate(rating_case(pair, SPECS, Service(1000.0 * 19 / 24, "driven"), Load(120e3 * 19 / 24, "driver")).case)
    assert b.pinion.s_h == pytest.approx(a.pinion.s_h, rel=1e-12)
    assert b.wheel.s_f == pytest.approx(a.wheel.s_f, rel=1e-12)
    # the wheel driving the pinion: T_1 is still the pinion's
    rev = GearPair(pair.gear2, pair.gear1)
    c = rate(rating_case(rev, SPECS, Service(1000.0 * 19 / 24, "driver"), Load(120e3 * 19 / 24, "driven")).case)
    assert c.tangential_force == pytest.approx(a.tangential_force, rel=1e-12)


def test_nominal_contact_stress_is_hertz_at_the_pitch_point():
    """σ_H0 / Z_ε (Z_D = 1 here) is Hertz's line contact at the pitch point: p0 = sqrt(w E* / (π ρ))."""
    pair = spur()
    nc = nominal_contact(pair, 120e3, (E, NU))
    al = path_of_contact(pair).alpha_wt
    g1, g2 = pair.gear1, pair.gear2
    rho = 1.0 / (1.0 / (g1.r_b * math.tan(al)) + 1.0 / (g2.r_b * math.tan(al)))
    w = 120e3 / g2.r_b / g1.face_width
    p0 = math.sqrt(w * E / (2 * (1 - NU ** 2)) / (math.pi * rho))
    assert nc.z_d == 1.0
    assert nc.at_inner_point_wheel == pytest.approx(p0, rel=1e-9)
    assert nc.at_inner_point_pinion == pytest.approx(p0 * nc.z_b, rel=1e-9) and nc.z_b > 1.0


def test_mesh_misalignment_of_method_c_follows_the_pair():
    pair = spur()
    assert mesh_misalignment(pair, math.radians(20)) == 0.0
    tilted = pair.with_misalignment(d_gamma=5 * ARCMIN)  # f_ma 19 µm, above ISO's F_βx,min of grade 6
    f = mesh_misalignment(tilted, math.radians(20))
    assert f == pytest.approx(14.0 * 5 * ARCMIN * math.cos(math.radians(20)) * 1e3, rel=1e-12)  # (R1) [µm]
    iso = rate(rating_case(pair, SPECS, Service(1000.0), Load(120e3)).case)
    mis = rate(rating_case(tilted, SPECS, Service(1000.0), Load(120e3)).case)
    assert mis.factors["K_Hbeta"].value > iso.factors["K_Hbeta"].value


def test_k_gamma_passed_in_scales_the_stresses():
    """K_γ from a loaded train, passed in: with K_v, K_Hβ, K_Hα fixed, σ_H ∝ √K_γ and σ_F ∝ K_γ."""
    pair = spur()
    fixed = {"k_v": Given(1.05), "k_h_beta": Given(1.2), "k_h_alpha": Given(1.0)}
    a = rate(rating_case(pair, SPECS, Service(1000.0), Load(120e3, given=fixed)).case)
    g = Given(1.18, Source.GEARFE, "loaded train: most loaded planet over the mean")
    b = rate(rating_case(pair, SPECS, Service(1000.0), Load(120e3, given={**fixed, "k_gamma": g})).case)
    assert b.pinion.factors["K_gamma"].source is Source.GEARFE
    assert b.pinion.sigma_h / a.pinion.sigma_h == pytest.approx(math.sqrt(1.18), rel=1e-12)
    assert b.wheel.sigma_f / a.wheel.sigma_f == pytest.approx(1.18, rel=1e-12)


def test_cases_outside_iso_assumptions_are_rated_with_a_warning():
    short = spur(addendum=0.55, tool_addendum=0.85)  # ε_α = 0.94
    rp = rating_case(short, SPECS, Service(1000.0), Load(120e3))
    r = rate(rp.case)
    codes = {w.code for w in (*rp.warnings, *r.warnings)}
    assert "eps_alpha_below_1" in codes and "root_load_point" in codes
    assert r.pinion.s_f > 0
    g1 = Gear("pinion", 19, 3.0, math.radians(20), 30.0, helix=math.radians(35), hand=1)
    g2 = Gear("wheel", 41, 3.0, math.radians(20), 30.0, helix=math.radians(35), hand=-1)
    r = rate(rating_case(GearPair(g1, g2), SPECS, Service(1000.0), Load(300e3)).case)
    assert "helix_above_30deg" in {w.code for w in r.warnings}


def test_gears_of_different_racks_are_refused():
    pair = spur()
    other = GearPair(pair.gear1, replace(pair.gear2, module=4.0))
    with pytest.raises(ValueError, match="gears.wheel.module_mm"):
        pair_data(other)
    with pytest.raises(ValueError, match="rating.gears.wheel"):
        rating_case(pair, {"pinion": SPECS["pinion"]}, Service(1000.0), Load(120e3))


def test_internal_pair_rates_the_ring_as_the_wheel():
    p = Gear("pinion", 24, 2.0, math.radians(20), 20.0)
    ring = Gear("ring", 72, 2.0, math.radians(20), 20.0, internal=True)
    rp = rating_case(GearPair(p, ring), {"pinion": GearSpec(EH, 6), "ring": GearSpec(iso_material("V (alloy)", "MQ", 300,
                                                                                                  yield_strength=700.0,
                                                                                                  brinell_hardness=290.0), 7)},
                     Service(1500.0), Load(100e3))
    assert rp.case.pair.internal and rp.wheel == "ring"
    r = rate(rp.case)
    assert r.wheel.factors["Z_D"].value == 1.0 and r.wheel.s_h > 0
    assert Misalignment() == GearPair(p, ring).misalignment
