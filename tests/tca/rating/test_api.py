"""The public API: records, sources of factors, both ways of K_Hβ, validation, warnings, invariants (hypothesis)."""

import math
from dataclasses import replace

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import tca.rating as rating
from tca.rating import (DEG, Factor, GearBlank, GearRatingData, Given, Operation, PairData, RatingCase,
                    RatingInputError, Source, iso_material, rate)
from tca.rating.life import bending_life_curve, contact_life_curve, life_factor

EH = iso_material("Eh", "MQ", 700)


def base_case(**over):
    pair = PairData(4.0, 20 * DEG, 12 * DEG, GearBlank(21, 40.0, 0.2), GearBlank(67, 38.0, -0.1))
    gear = GearRatingData(EH, 6, 3.0, 10.0, 1.35, 2.05, 2.4)
    c = RatingCase(pair, gear, replace(gear, form_factor=1.25, stress_correction=2.15, notch_parameter=2.8),
                   Operation(400e3, 1500.0, 20000.0, 150.0, 1.25))
    return replace(c, **over)


def test_public_api_is_explicit():
    assert set(rating.__all__) <= set(dir(rating))
    for name in ("rate", "RatingCase", "PairRating", "GearRating", "Factor", "Given", "Source", "iso_material"):
        assert name in rating.__all__


def test_result_records_are_frozen_and_complete():
    r = rate(base_case())
    with pytest.raises(AttributeError):
        r.pinion.s_h = 2.0  # frozen
    with pytest.raises(TypeError):
        r.pinion.factors["K_v"] = Factor(1.0, Source.ISO)  # read-only mapping
    need = {"K_A", "K_gamma", "K_v", "K_Hbeta", "K_Fbeta", "K_Halpha", "K_Falpha", "Z_H", "Z_E", "Z_eps", "Z_beta",
            "Z_NT", "Z_L", "Z_v", "Z_R", "Z_W", "Z_X", "Y_F", "Y_S", "Y_beta", "Y_B", "Y_DT", "Y_ST", "Y_NT",
            "Y_deltarelT", "Y_RrelT", "Y_X"}
    for g, z in ((r.pinion, "Z_B"), (r.wheel, "Z_D")):
        assert need | {z} <= set(g.factors)
        for f in g.factors.values():
            assert isinstance(f, Factor) and f.source in Source and math.isfinite(f.value)
        for key in ("sigma_h0", "sigma_h", "sigma_hp", "s_h", "sigma_f0", "sigma_f", "sigma_fp", "s_f"):
            assert getattr(g, key) > 0
    # simplifications say so
    assert "taken as 1" in r.pinion.factors["K_gamma"].note
    assert "taken as 1" in r.pinion.factors["Z_X"].note
    assert "solid" in r.pinion.factors["Y_B"].note


def test_k_h_beta_computed_both_ways():
    """The same case with K_Hβ by ISO method C and with K_Hβ passed in from gearfe's analysis."""
    iso = rate(base_case())
    assert iso.pinion.factors["K_Hbeta"].source is Source.ISO and iso.face_load is not None
    k = 1.37
    fe = rate(base_case(k_h_beta=Given(k, Source.GEARFE, "loaded TCA, 3 load steps")))
    f = fe.pinion.factors
    assert f["K_Hbeta"] == Factor(k, Source.GEARFE, "loaded TCA, 3 load steps") and fe.face_load is None
    assert f["K_Fbeta"].source is Source.ISO and "gearfe" in f["K_Fbeta"].note  # (F4) from the gearfe value
    # σ_H scales with sqrt(K_Hβ) when K_Hα is not limited by it (K_Hα is given to hold it fixed)
    a = rate(base_case(k_h_beta=Given(1.2), k_h_alpha=Given(1.0)))
    b = rate(base_case(k_h_beta=Given(1.5), k_h_alpha=Given(1.0)))
    assert b.pinion.sigma_h / a.pinion.sigma_h == pytest.approx(math.sqrt(1.5 / 1.2), rel=1e-12)


def test_gearfe_k_halpha_and_k_gamma():
    r = rate(base_case(k_h_alpha=Given(1.1, Source.GEARFE), k_gamma=Given(1.15, Source.GEARFE, "3 planets, TCA")))
    f = r.wheel.factors
    assert f["K_Halpha"].source is Source.GEARFE and f["K_Falpha"].value == 1.1
    assert f["K_Falpha"].source is Source.GEARFE and "equates" in f["K_Falpha"].note
    assert f["K_gamma"].value == 1.15 and f["K_gamma"].source is Source.GEARFE


def test_given_iso_source_is_refused():
    with pytest.raises(RatingInputError) as e:
        Given(1.2, Source.ISO)
    assert e.value.key == "given.source"


@pytest.mark.parametrize("change,key", [
    (lambda c: replace(c, operation=replace(c.operation, speed=0.0)), "speed"),
    (lambda c: replace(c, operation=replace(c.operation, speed=-10.0)), "speed"),
    (lambda c: replace(c, operation=replace(c.operation, life_hours=0.0)), "life_hours"),
    (lambda c: replace(c, operation=replace(c.operation, torque=-1.0)), "torque"),
    (lambda c: replace(c, operation=replace(c.operation, application_factor=0.9)), "application_factor"),
    (lambda c: replace(c, long_life_contact=0.8), "long_life_contact"),
    (lambda c: replace(c, k_h_beta=Given(0.95)), "k_h_beta"),
    (lambda c: replace(c, pinion=replace(c.pinion, notch_parameter=8.5)), "notch_parameter"),
    (lambda c: replace(c, pinion=replace(c.pinion, root_roughness=45.0)), "root_roughness"),
    (lambda c: replace(c, pinion=replace(c.pinion, accuracy_grade=13)), "accuracy_grade"),
    (lambda c: replace(c, pair=replace(c.pair, normal_module=-2.0)), "normal_module"),
    (lambda c: replace(c, pair=replace(c.pair, helix_angle=50 * DEG)), "helix_angle_deg"),
])
def test_invalid_inputs_raise_one_line_errors(change, key):
    with pytest.raises(RatingInputError) as e:
        rate(change(base_case()))
    err = e.value
    assert isinstance(err, ValueError) and err.key == key and err.valid
    assert str(err).startswith(f"{key} = ") and "\n" not in str(err)


def test_out_of_assumption_cases_are_rated_with_warnings():
    # ε_α < 1: short tips
    pair = PairData(4.0, 20 * DEG, 12 * DEG, GearBlank(21, 40.0, 0.0, tip_diameter=89.3),
                    GearBlank(67, 40.0, 0.0, tip_diameter=276.5))
    r = rate(base_case(pair=pair))
    assert r.geometry.eps_alpha < 1.0
    assert "eps_alpha_below_1" in {w.code for w in r.warnings}
    assert math.isfinite(r.pinion.s_h) and math.isfinite(r.pinion.s_f)
    # β > 30°
    r = rate(base_case(pair=replace(base_case().pair, helix_angle=35 * DEG)))
    assert "helix_above_30deg" in {w.code for w in r.warnings}
    assert r.pinion.factors["Y_beta"].value == pytest.approx(0.75)  # ε_β >= 1, β taken as 30°
    assert rate(base_case()).warnings == ()


def test_internal_pair_rates():
    pair = PairData(3.0, 20 * DEG, 0.0, GearBlank(24, 30.0, 0.2), GearBlank(75, 30.0, 0.1), internal=True)
    r = rate(base_case(pair=pair))
    assert r.geometry.internal and r.wheel.factors["Z_D"].value == 1.0
    assert r.pinion.sigma_h0 < rate(base_case(pair=replace(pair, internal=False))).pinion.sigma_h0  # (u-1)/u < (u+1)/u


GIVEN_LOADS = dict(k_v=Given(1.05), k_h_beta=Given(1.3), k_f_beta=Given(1.25), k_h_alpha=Given(1.1),
                   k_f_alpha=Given(1.1))


@settings(max_examples=40, deadline=None)
@given(t=st.floats(1e3, 5e6), scale=st.floats(1.1, 10.0))
def test_safeties_scale_with_torque(t, scale):
    """With the load factors given (load-independent): S_H ~ 1/sqrt(T), S_F ~ 1/T (ISO 6336-2 (H1), -3 (B1))."""
    def rate_at(torque):
        c = base_case(**GIVEN_LOADS)
        return rate(replace(c, operation=replace(c.operation, torque=torque)))

    a, b = rate_at(t), rate_at(t * scale)
    for ga, gb in ((a.pinion, b.pinion), (a.wheel, b.wheel)):
        assert gb.s_h == pytest.approx(ga.s_h / math.sqrt(scale), rel=1e-10)
        assert gb.s_f == pytest.approx(ga.s_f / scale, rel=1e-10)


@settings(max_examples=40, deadline=None)
@given(t=st.floats(2e4, 2e6), scale=st.floats(1.05, 4.0))
def test_safeties_fall_with_torque_when_iso_computes_the_factors(t, scale):
    """K_v, K_Hβ, K_Hα fall with load, but T K(T) rises: the safeties still fall."""
    def rate_at(torque):
        c = base_case()
        return rate(replace(c, operation=replace(c.operation, torque=torque)))

    a, b = rate_at(t), rate_at(t * scale)
    assert b.pinion.s_h < a.pinion.s_h and b.wheel.s_f < a.wheel.s_f


@settings(max_examples=60, deadline=None)
@given(kind=st.sampled_from(["Eh", "V (alloy)", "St", "NT (nitr.)", "NV (nitrocar.)", "GG", "IF"]),
       limited=st.booleans(), log_n=st.floats(2.0, 11.0), z10=st.floats(0.85, 1.0))
def test_life_factors(kind, limited, log_n, z10):
    """Z_NT = 1 at the reference cycles, non-increasing in N_L, static values below N_st; same for Y_NT."""
    for curve in (contact_life_curve(kind, limited), bending_life_curve(kind)):
        assert life_factor(curve, curve.n_ref, z10) == pytest.approx(1.0, abs=1e-12)
        n = 10.0 ** log_n
        z, z_next = life_factor(curve, n, z10), life_factor(curve, n * 1.01, z10)
        assert z_next <= z + 1e-15
        assert z10 - 1e-12 <= z <= curve.z_static


@settings(max_examples=40, deadline=None)
@given(z1=st.integers(12, 40), ratio=st.floats(1.0, 5.0), x1=st.floats(-0.3, 0.6), x2=st.floats(-0.3, 0.6),
       beta_deg=st.floats(0.0, 30.0), mn=st.sampled_from([1.0, 2.5, 4.0, 8.0]))
def test_centre_distance_and_shifts_agree(z1, ratio, x1, x2, beta_deg, mn):
    """(G3)/(G4): the centre distance from the shifts, given back as a, gives the same α_wt and x1 + x2."""
    z2 = max(z1, int(round(z1 * ratio)))
    pair = PairData(mn, 20 * DEG, beta_deg * DEG, GearBlank(z1, 10 * mn, x1), GearBlank(z2, 10 * mn, x2))
    try:
        g = rating.pair_geometry(pair)
    except RatingInputError:
        assume(False)
    g2 = rating.pair_geometry(replace(pair, centre_distance=g.centre_distance))
    assert g2.working_pressure_angle == pytest.approx(g.working_pressure_angle, abs=1e-12)
    assert g2.x_sum_from_centre_distance == pytest.approx(x1 + x2, abs=1e-9)
    assert g.eps_alpha > 0 and g.eps_gamma == pytest.approx(g.eps_alpha + g.eps_beta)
