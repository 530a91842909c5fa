"""ISO 6336-3 method B (tca.rating.root_stress) against the generated tooth: the root chord s_Fn and fillet radius ρ_F.

ISO's s_Fn and ρ_F are closed forms of the trochoid cut by the basic rack's tip rounding; the
gear's own fillet surface (tca.geometry.profile: envelope of the rack-cutter) is an independent path to the
same two numbers: the fillet point whose tangent makes 30° with the tooth centre line, its chord
2|y| and its radius of curvature. Y_F and Y_S themselves are not compared with published worked
values: no published Y_F / Y_S for given gear data (ISO/TR 6336-30, DIN 3990 examples, textbooks) was
available to this project's sources (docs/standard_gears.md says what was searched). They are checked
through the quantities they are built from, their trends, the rack limit that the external (E1)-(E9) and
internal (I1)-(I4) equations share, another implementation of the same equations with the load at the tip
(DIN 3990-11 Annex D, hanslhansl/din3990), and the FE root stress (tests/pipelines/models/stress/test_standard_gears.py,
tests/pipelines/models/stress/test_internal_root.py).
"""

import math

import numpy as np
import pytest

from tca.errors import InputError
from tca.geometry.gear import Gear
from tca.rating.root_stress import root_factors, sigma_f0


def _generated(g: Gear, side: int = 1) -> tuple[float, float]:
    """(s_Fn, ρ_F) [mm] of the generated fillet of flank ``side`` at its 30° tangent, section z = 0 of a spur gear.

    s_Fn is twice that flank's half-chord (the distance of the 30° point from the tooth centre line).
    """
    srf = g.surface(side, "fillet")
    u = np.linspace(*srf.u_range, 20001)
    sp = srf.evaluate(u, np.zeros_like(u))
    d1, d2 = sp.r_u[:, :2], sp.r_uu[:, :2]
    ang = np.degrees(np.arctan2(np.abs(d1[:, 1]), np.abs(d1[:, 0])))  # tangent against the centre line (x axis)
    i = int(np.argmin(np.abs(ang - 30.0)))
    kappa = np.abs(d1[i, 0] * d2[i, 1] - d1[i, 1] * d2[i, 0]) / np.linalg.norm(d1[i]) ** 3
    return 2 * abs(sp.r[i, 1]), 1.0 / kappa


@pytest.mark.parametrize("z, x", [(19, 0.0), (24, 0.0), (16, 0.2), (40, -0.2)])
def test_root_chord_and_fillet_radius_match_the_generated_tooth(z, x):
    g = Gear("g", z, 4.5, math.radians(20), 14.0, profile_shift=x)
    rf = root_factors(g, 1.5)
    s_fn, rho = _generated(g)
    # the sampled 30° point is within 1e-3 deg of the exact one: 1e-4 relative on the chord, 1e-3 on the radius
    assert rf.s_fn == pytest.approx(s_fn, rel=1e-4)
    assert rf.rho_f == pytest.approx(rho, rel=1e-3)


def test_factors_in_their_published_ranges_and_trends():
    """ISO 6336-3 figures: Y_F falls and Y_S rises with z; positive shift lowers Y_F (standard rack, load at D)."""
    yf = [root_factors(Gear("g", z, 4.5, math.radians(20), 14.0), 1.55).y_f for z in (19, 25, 40, 80)]
    ys = [root_factors(Gear("g", z, 4.5, math.radians(20), 14.0), 1.55).y_s for z in (19, 25, 40, 80)]
    assert all(a > b for a, b in zip(yf, yf[1:])) and all(a < b for a, b in zip(ys, ys[1:]))
    assert 1.2 < min(yf) and max(yf) < 2.2 and 1.6 < min(ys) and max(ys) < 2.4
    shifted = root_factors(Gear("g", 18, 4.5, math.radians(20), 14.0, profile_shift=0.4), 1.55).y_f
    assert shifted < yf[0]


def test_sigma_f0_is_linear_in_torque_and_rejects_what_method_b_does_not_cover():
    g = Gear("g", 19, 4.5, math.radians(20), 14.0)
    assert sigma_f0(g, 2e5, 1.57) == pytest.approx(2 * sigma_f0(g, 1e5, 1.57), rel=1e-12)
    with pytest.raises(InputError, match="eps_alpha"):
        root_factors(g, 2.3)
    with pytest.raises(InputError, match="eps_alpha"):
        root_factors(Gear("r", 60, 4.5, math.radians(20), 14.0, internal=True), 0.9)


@pytest.mark.parametrize("z, a_pos, a_neg", [(40, 0.002, 0.002), (40, 0.008, 0.008), (40, 0.008, 0.005)])
def test_parabolic_rack_fillet_matches_the_generated_tooth(z, a_pos, a_neg):
    """The crowned rack's tip rounding moves toward the tooth (Δη in E): ISO's trochoid is then exact."""
    g = Gear("g", z, 4.5, math.radians(20), 14.0, parabola_pos=a_pos, parabola_neg=a_neg)
    rf = root_factors(g, 1.5)
    (s_p, rho_p), (s_n, rho_n) = _generated(g, 1), _generated(g, -1)
    straight = root_factors(Gear("g", z, 4.5, math.radians(20), 14.0), 1.5)
    assert rf.s_fn < straight.s_fn  # the bulged rack flank cuts deeper into the fillet
    # same sampling tolerances as the straight rack above; the chord is the sum of the two half-chords
    assert rf.s_fn == pytest.approx(0.5 * (s_p + s_n), rel=1e-4)
    assert rf.rho_f == pytest.approx(0.5 * (rho_p + rho_n), rel=1e-3)


def test_internal_gear_substitute_rack_is_the_limit_of_the_generated_ring():
    """(I1), (I4): the substitute rack's chord and rounding are the limit z -> inf of the rack-generated ring.

    The generated ring's 30° chord and fillet radius approach them as 1/z (measured: chord +1.35 % at z = 400,
    +0.26 % at z = 2000; radius -18 % and -3.3 %); the test asserts that convergence, not a tolerance at one z.
    """
    dev = []
    for z in (400, 2000):
        g = Gear("r", z, 4.5, math.radians(20), 14.0, internal=True)
        rf = root_factors(g, 1.6)
        s_fn, rho = _generated(g)
        dev.append((s_fn / rf.s_fn - 1, rho / rf.rho_f - 1))
    for k in (0, 1):
        assert abs(dev[1][k]) < abs(dev[0][k]) / 4  # 1/z: a factor 5 between z = 400 and 2000
    assert abs(dev[1][0]) < 0.005


def test_internal_and_external_equations_share_the_rack_limit():
    """(E1)-(E9) with z -> inf and (I1)-(I4) with z -> inf both describe a rack tooth: two code paths, one limit."""
    for x in (0.0, 0.3):
        e = root_factors(Gear("e", 2000, 4.5, math.radians(20), 14.0, profile_shift=x), 1.6)
        i = root_factors(Gear("i", 2000, 4.5, math.radians(20), 14.0, internal=True, profile_shift=-x), 1.6)
        # 1/z terms of opposite sign: chord and arm within 0.7 %, the fillet radius within 4 % at z = 2000
        assert i.s_fn == pytest.approx(e.s_fn, rel=0.007)
        assert i.h_fe == pytest.approx(e.h_fe, rel=0.007)
        assert i.rho_f == pytest.approx(e.rho_f, rel=0.04)
        assert i.y_f == pytest.approx(e.y_f, rel=0.007)


def test_internal_gear_factors_follow_the_substitute_rack():
    """(I1)-(I4) by hand for a 60-tooth ring (m = 4.5, α = 20°, h_fP = 1.25 m, ρ_fP = 0.25 m) loaded at ε_α = 1.6.

    The chord does not depend on z or x (a rack tooth); Y_F falls as the ring's teeth grow in number (the load
    point moves toward the tip of the virtual internal gear: a shorter arm).
    """
    m, a = 4.5, math.radians(20)
    g = Gear("r", 60, m, a, 14.0, internal=True)
    rf = root_factors(g, 1.6)
    half = math.pi / 4 * m + (1.25 * m - 0.25 * m) * math.tan(a) + 0.25 * m / math.cos(a) - 0.25 * m * math.sqrt(3) / 2
    assert rf.s_fn == pytest.approx(2 * half, rel=1e-12)
    assert rf.rho_f == pytest.approx(0.25 * m, rel=1e-12) and rf.alpha_fen == pytest.approx(a, rel=1e-12)
    # load point: one base pitch times (ε_α - 1) beyond the tip contact, on the virtual (spur: real) ring
    r_b, r_a, r_f = 30 * m * math.cos(a), 30 * m - m, 30 * m + 1.25 * m
    r_e = math.hypot(math.sqrt(r_a ** 2 - r_b ** 2) + math.pi * m * math.cos(a) * 0.6, r_b)
    assert rf.d_en == pytest.approx(2 * r_e, rel=1e-12)
    h_e = r_f - r_e
    arm = h_e - (math.pi / 4 * m + (1.25 * m - h_e) * math.tan(a)) * math.tan(a) - 0.25 * m / 2
    assert rf.h_fe == pytest.approx(arm, rel=1e-12)
    for x in (-0.3, 0.3):
        assert root_factors(Gear("r", 60, m, a, 14.0, internal=True, profile_shift=x), 1.6).s_fn == pytest.approx(rf.s_fn)
    yf = [root_factors(Gear("r", z, m, a, 14.0, internal=True), 1.6).y_f for z in (40, 60, 120)]
    assert yf[0] > yf[1] > yf[2]


# Another implementation: hanslhansl/din3990 (GitHub, commit 5024995, din3990/din3990_11.py), DIN 3990-11:1989
# Annex D, Eqs. D.5.01-D.5.16 (s_Fn, h_Fa, ρ_F, α_Fan, Y_Fa) and D.4.01 (Y_Sa), for the load at the tooth tip.
# Method B with ε_α = 1 puts the load at the tip (d_en = d_an), so the two must agree. Inputs: m = 4.5 mm,
# α = 20°, h_fP = 1.25 m, ρ_fP = 0.25 m, s_pr = 0, spur; d_a, d_f as this project generates them (internal gears
# in DIN's sign convention, z and diameters negative). Run 2026-11-24; these are that code's outputs, not
# published worked values (none was found, see the module docstring).
#                 (s_Fn [mm], h_Fa [mm], ρ_F [mm], α_Fan [deg], Y_Fa), Y_Sa
DIN3990_EXTERNAL = {
    (19, 0.0): ((8.56460114, 8.736631316, 2.250604782, 29.88811259, 2.967063537), 1.59065431),
    (24, 0.0): ((8.957312499, 8.723787236, 2.177641666, 28.26427181, 2.751639029), 1.64345157),
    (16, 0.2): ((8.84994693, 8.953888965, 1.945859295, 33.42052733, 2.741656388), 1.67584725),
    (40, -0.2): ((9.260524366, 8.649224578, 2.29557632, 24.27536341, 2.641671547), 1.65036310),
}
DIN3990_INTERNAL = {  # (z, x, h_a / m); DIN's Y_Sa is undefined here: its ρ_F = ρ_fP/2 gives q_s = 9.6 >= 8
    (72, 0.0, 1.0): (10.79015841, 8.872257501, 0.5625, 20.0, 2.057511451),
    (72, 0.5, 0.3): (10.79015841, 5.304963357, 0.5625, 20.0, 1.230241892),
}


@pytest.mark.parametrize("z, x", sorted(DIN3990_EXTERNAL))
def test_external_factors_at_the_tip_match_din_3990_11_as_implemented_elsewhere(z, x):
    (s_fn, h_fa, rho_f, a_fan, y_fa), y_sa = DIN3990_EXTERNAL[(z, x)]
    rf = root_factors(Gear("g", z, 4.5, math.radians(20), 14.0, profile_shift=x), 1.0)
    # that code stops the fixed point for ϑ after 5 iterations (ours converges to 1e-12 and matches the generated
    # fillet to 1e-5): measured 1.1e-3 on s_Fn, 2.1e-3 on Y_Fa; h_Fa, ρ_F within 1.5e-4, α_Fan exact
    assert rf.s_fn == pytest.approx(s_fn, rel=2e-3)
    assert rf.h_fe == pytest.approx(h_fa, rel=3e-4) and rf.rho_f == pytest.approx(rho_f, rel=3e-4)
    assert math.degrees(rf.alpha_fen) == pytest.approx(a_fan, rel=1e-9)
    assert rf.y_f == pytest.approx(y_fa, rel=4e-3) and rf.y_s == pytest.approx(y_sa, rel=2e-3)


@pytest.mark.parametrize("z, x, ha", sorted(DIN3990_INTERNAL))
def test_internal_factors_at_the_tip_match_din_3990_11_as_implemented_elsewhere(z, x, ha):
    """(I1)-(I4) against DIN 3990-11 D.5.05 / D.5.11 / D.5.15 / D.5.16: equal, except ρ_F (DIN halves ρ_fP)."""
    s_fn, h_fa, rho_f, a_fan, y_fa = DIN3990_INTERNAL[(z, x, ha)]
    rf = root_factors(Gear("r", z, 4.5, math.radians(20), 14.0, internal=True, profile_shift=x, addendum=ha), 1.0)
    assert rf.s_fn == pytest.approx(s_fn, rel=1e-9) and rf.h_fe == pytest.approx(h_fa, rel=1e-9)
    assert math.degrees(rf.alpha_fen) == pytest.approx(a_fan, rel=1e-9) and rf.y_f == pytest.approx(y_fa, rel=1e-9)
    assert rf.rho_f == pytest.approx(2 * rho_f, rel=1e-12)  # (I4) keeps the substitute rack's own rounding


@pytest.mark.parametrize("a_c", [0.002, 0.008])
def test_parabolic_rack_thins_the_internal_chord_as_it_thins_the_generated_ring(a_c):
    """(I1) with Δη: the crowned rack's change of the chord equals the generated ring's (z = 2000, rack limit)."""
    plain = Gear("r", 2000, 4.5, math.radians(20), 14.0, internal=True)
    crowned = Gear("r", 2000, 4.5, math.radians(20), 14.0, internal=True, parabola_pos=a_c, parabola_neg=a_c)
    d_iso = root_factors(crowned, 1.6).s_fn - root_factors(plain, 1.6).s_fn
    d_gen = _generated(crowned)[0] - _generated(plain)[0]
    assert d_iso < 0
    assert d_iso == pytest.approx(d_gen, abs=2e-3)  # mm; both chords carry the same 1/z offset (0.03 mm)
