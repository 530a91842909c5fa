"""Factor by factor: closed forms, derivations independent of the code path, and published values.

Sources: KISSsoft 03/2017 reports in gfsReboucas/Drivetrain (@NREL_5MW/stage_02.rtf, stage_03.rtf) for the
running-in allowances and life factors; ISO/TR 6336-30:2017 Example 1 (quoted in gfsReboucas/Drivetrain,
MATISO_6336.m) for Z_NT; the rest are closed-form derivations written out in the test.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from tca.rating import DEG, GearBlank, Material, PairData, iso_material, pair_geometry, tolerances
from tca.rating.dynamics import ToothDeviations, cv_coefficients, dynamic_factor, running_in_tip_relief
from tca.rating.face_load import ShaftData, face_load_factor
from tca.rating.geometry import inv, inv_inverse
from tca.rating.life import bending_life_curve, contact_life_curve, life_factor
from tca.rating.running_in import helix_allowance, profile_allowance

EH = iso_material("Eh", "MQ", 700)
V_RING = Material("V (alloy)", 700.0, 290.0, brinell_hardness=240.0, yield_strength=1000.0)


def test_running_in_allowances_reproduce_the_report():
    """y_f is printed to 3 decimals in stage 2: 1.725 (sun-planet), 4.098 (planet-ring, Eh against V)."""
    q6 = [tolerances(6, d, 21.0, 550.0, 20 * DEG) for d in (378.0, 756.0, 1953.0)]
    assert abs(profile_allowance(EH, EH, max(q6[0].f_f_alpha, q6[1].f_f_alpha), 4.88) - 1.725) < 5e-4
    assert abs(profile_allowance(EH, V_RING, max(q6[1].f_f_alpha, q6[2].f_f_alpha), 4.88) - 4.098) < 5e-4
    # y_p (printed 1.342 and 3.142) comes out 0.22 % and 0.13 % lower with f_pb = f_pt cos α_t (A7); the report's
    # f_pb is slightly larger for a reason not found (README). Checked to the size of that offset, not hidden:
    yp12 = profile_allowance(EH, EH, max(q6[0].f_pb, q6[1].f_pb), 4.88)
    yp23 = profile_allowance(EH, V_RING, max(q6[1].f_pb, q6[2].f_pb), 4.88)
    assert abs(yp12 / 1.342 - 1) < 2.5e-3 and abs(yp23 / 3.142 - 1) < 1.5e-3


def test_running_in_caps():
    """(R1)-(R3): hardened gears cap at 3 µm / 6 µm; through-hardened ones cap the deviation with speed."""
    assert profile_allowance(EH, EH, 100.0, 1.0) == 3.0
    assert helix_allowance(EH, EH, 100.0, 1.0) == 6.0
    v = Material("V (alloy)", 800.0, 300.0)
    assert profile_allowance(v, v, 100.0, 4.0) == pytest.approx(160 / 800 * 100)
    assert profile_allowance(v, v, 100.0, 8.0) == pytest.approx(160 / 800 * 80)
    assert profile_allowance(v, v, 100.0, 12.0) == pytest.approx(160 / 800 * 40)


def test_tip_relief_of_running_in():
    """(D11) gives the C_a = 2.0 µm (σ_Hlim 1500) and 8.5 µm (σ_Hlim 700) the reports print for 'no modification'."""
    assert round(running_in_tip_relief(1500.0), 1) == 2.0
    assert round(running_in_tip_relief(700.0), 1) == 8.5


@pytest.mark.parametrize("cycles,curve,expected", [
    (1.08e9, "contact", 0.91), (1.783e8, "contact", 0.962),  # ISO/TR 6336-30:2017 Example 1
    (3.0962e9, "contact", 0.881), (3.0962e9, "bending", 0.870),  # KISSsoft stage 3, wheel
    (12255.788e6, "contact", 0.850), (12255.788e6, "bending", 0.850),  # stage 3, pinion (beyond 10^10)
])
def test_life_factors_against_published_values(cycles, curve, expected):
    c = contact_life_curve("Eh") if curve == "contact" else bending_life_curve("Eh")
    assert abs(life_factor(c, cycles) - expected) <= (5e-3 if expected == 0.91 else 5e-4)  # half the printed digit


def test_life_curves_pass_through_their_points():
    """(L2): static value up to N_st, 1 at N_ref, Z_10 at 10^10, and the knee (10^7, 1.3) for limited pitting."""
    kinds = ["Eh", "V (alloy)", "NT (nitr.)", "NV (nitrocar.)", "St", "GG"]
    curves = [contact_life_curve(k) for k in kinds] + [contact_life_curve("Eh", True)] + \
             [bending_life_curve(k) for k in kinds]
    for c in curves:
        assert life_factor(c, c.n_static) == c.z_static
        assert life_factor(c, c.n_static * (1 + 1e-12)) == pytest.approx(c.z_static, rel=1e-9), c.name
        assert life_factor(c, c.n_ref) == pytest.approx(1.0, abs=1e-12), c.name
        assert life_factor(c, 1e10) == pytest.approx(0.85, abs=1e-12) and life_factor(c, 1e12) == 0.85
        assert life_factor(c, 1e10, long_life=1.0) == 1.0
    assert life_factor(contact_life_curve("Eh", True), 1e7) == pytest.approx(1.3, abs=1e-12)


def test_life_curves_match_the_exponents_iso_prints_to_their_rounding():
    """The point form against the power laws printed in ISO 6336-2/-3: exponents 0.0756, 0.0306 (Z_NT), 0.115, 0.02
    (Y_NT Eh/IF), 0.16 (Y_NT V), 0.0875, 0.0191 (Z_NT NT/NV), each to one unit of its last digit (0.0306 is the
    truncation of the point form's 0.030674, so half a unit would not hold)."""
    def slope(curve, n0, n1):
        return -math.log(life_factor(curve, n1) / life_factor(curve, n0)) / math.log(n1 / n0)

    for curve, n0, n1, printed, unit in ((contact_life_curve("Eh"), 1e6, 1e7, 0.0756, 1e-4),
                                         (contact_life_curve("Eh"), 1e8, 1e9, 0.0306, 1e-4),
                                         (bending_life_curve("Eh"), 1e4, 1e5, 0.115, 1e-3),
                                         (bending_life_curve("Eh"), 1e7, 1e8, 0.02, 1e-2),
                                         (bending_life_curve("V (alloy)"), 1e5, 1e6, 0.16, 1e-2),
                                         (contact_life_curve("NT (nitr.)"), 2e5, 1e6, 0.0875, 1e-4),
                                         (contact_life_curve("NT (nitr.)"), 1e8, 1e9, 0.0191, 1e-4)):
        assert abs(slope(curve, n0, n1) - printed) < unit, (curve.name, printed)


def test_zone_factor_closed_form_for_a_standard_spur_pair():
    """Z_H = 2/sqrt(sin 2α) for an unshifted spur pair (α_wt = α_t = α): 2.4946 at 20°."""
    from tca.rating.contact import contact_factors

    g = pair_geometry(PairData(2.0, 20 * DEG, 0.0, GearBlank(20, 20.0), GearBlank(40, 20.0)))
    cf = contact_factors(g, (206000.0, 206000.0), (0.3, 0.3))
    assert cf.z_h == pytest.approx(2 / math.sqrt(math.sin(40 * DEG)), rel=1e-12)
    assert cf.z_e == pytest.approx(math.sqrt(206000 / (2 * math.pi * (1 - 0.09))), rel=1e-12)


def test_single_pair_contact_factor_is_the_iso_m1_formula():
    """(H7) written on the line of action equals ISO's M_1, M_2 bracket formulas (external pair)."""
    from tca.rating.contact import contact_factors

    g = pair_geometry(PairData(45.0, 20 * DEG, 0.0, GearBlank(17, 491.0, 0.8021, tip_diameter=905.47),
                               GearBlank(19, 491.0, 0.617, tip_diameter=978.808), centre_distance=863.0))
    cf = contact_factors(g, (206000.0, 206000.0), (0.3, 0.3))
    (da1, da2), (db1, db2), (z1, z2) = g.tip_diameter, g.base_diameter, g.teeth
    ea, awt = g.eps_alpha, g.working_pressure_angle
    m1 = math.tan(awt) / math.sqrt((math.sqrt(da1**2 / db1**2 - 1) - 2 * math.pi / z1)
                                   * (math.sqrt(da2**2 / db2**2 - 1) - (ea - 1) * 2 * math.pi / z2))
    m2 = math.tan(awt) / math.sqrt((math.sqrt(da2**2 / db2**2 - 1) - 2 * math.pi / z2)
                                   * (math.sqrt(da1**2 / db1**2 - 1) - (ea - 1) * 2 * math.pi / z1))
    assert cf.m1 == pytest.approx(m1, rel=1e-12) and cf.m2 == pytest.approx(m2, rel=1e-12)
    # KISSsoft stage 1 (planet z = 17 is the pinion of this sun-planet mesh): Z_B 1.05 planet, Z_D 1.04 sun
    assert round(cf.z_b, 2) == 1.05 and round(cf.z_d, 2) == 1.04


def test_face_load_factor_against_an_integrated_linear_load():
    """(F1) against a direct solution: line load w(y) = max(0, w0 + c F_βy y / b) over the face, w0 such that the
    integral is F_m; K_Hβ = max w / (F_m / b). Both branches (full and partial contact)."""
    b, c = 100.0, 15.0
    for f_by in (2.0, 10.0, 40.0):
        wm = 400.0
        slope = c * f_by / b

        def total(w0):
            return quad(lambda y: max(0.0, w0 + slope * y), 0.0, b, limit=200)[0] - wm * b

        w0 = brentq(total, -slope * b, wm)
        k_direct = (w0 + slope * b) / wm
        r = face_load_factor(mean_line_load=wm, pinion_diameter=1e9, face_width=b, c_gamma_beta=c,
                             total_helix_deviation=0.0, shaft=ShaftData(mesh_misalignment=f_by),
                             running_in=lambda fbx: 0.0)
        assert r.f_beta_y == pytest.approx(f_by)
        assert r.k_h_beta == pytest.approx(k_direct, rel=1e-7)


def test_face_load_factor_is_continuous_at_the_switch():
    def k(f_by):
        return face_load_factor(mean_line_load=100.0, pinion_diameter=1e9, face_width=50.0, c_gamma_beta=10.0,
                                total_helix_deviation=0.0, shaft=ShaftData(mesh_misalignment=f_by),
                                running_in=lambda fbx: 0.0).k_h_beta

    x = 20.0  # F_βy c / (F_m/b) = 2
    assert k(x * (1 - 1e-9)) == pytest.approx(2.0, abs=1e-8) and k(x * (1 + 1e-9)) == pytest.approx(2.0, abs=1e-8)


def test_dynamic_factor_intermediate_range_joins_its_neighbours():
    """(D8) joins (D7) at N = 1.15 and (D9) at N = 1.5."""
    g = pair_geometry(PairData(4.0, 20 * DEG, 0.0, GearBlank(20, 40.0), GearBlank(60, 40.0)))
    common = dict(line_load=300.0, c_prime=14.0, c_gamma_alpha=20.0, reduced_mass=0.01,
                  deviations=ToothDeviations(f_pb_eff=8.0, f_falpha_eff=9.0, tip_relief=5.0))
    n_e1 = dynamic_factor(g, pinion_speed=1.0, **common).resonance_speed
    kv = [dynamic_factor(g, pinion_speed=n * n_e1, **common).k_v for n in (1.15, 1.15 + 1e-9, 1.5 - 1e-9, 1.5)]
    assert kv[0] == pytest.approx(kv[1], abs=1e-8) and kv[2] == pytest.approx(kv[3], abs=1e-8)
    # the main resonance range is rated and flagged
    r = dynamic_factor(g, pinion_speed=1.0 * n_e1, **common)
    assert r.speed_range == "main resonance" and r.warnings[0].code == "main_resonance"


def test_cv_coefficients_are_continuous_in_eps_gamma_where_iso_makes_them():
    """C_v7 (D10) is continuous at ε_γ = 1.5 and 2.5 (0.125 sin(π(ε_γ - 2)) + 0.875 hits 0.75 and 1)."""
    for e in (1.5, 2.5):
        assert cv_coefficients(e - 1e-9)[6] == pytest.approx(cv_coefficients(e + 1e-9)[6], abs=1e-8)


def test_involute_inverse():
    for a in np.linspace(0.01, 1.3, 50):
        assert inv_inverse(inv(a)) == pytest.approx(a, abs=1e-13)
