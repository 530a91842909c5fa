"""ISO 6336-5 allowable stress numbers (M1) and the material errors.

Cross-check sources (facts only): the ME rows as transcribed in the public repository waa552/fyp-website (data.js:
A, B of contact and bending and the hardness range per material); the case-hardened MQ values of the KISSsoft
03/2017 reports in gfsReboucas/Drivetrain (18CrNiMo7-6: σ_Flim 430, σ_Hlim 1500 MPa).
"""

import pytest

from tca.rating import ISO_6336_5_TABLE, MaterialKind, Quality, RatingInputError, iso_material

# waa552/fyp-website data.js: (A_H, B_H, A_F, B_F, x_min, x_max)
FYP_ME = {
    MaterialKind.ST: (1.520, 250, 0.386, 147, 110, 210),
    MaterialKind.ST_CAST: (1.143, 237, 0.254, 137, 140, 210),
    MaterialKind.V_CARBON: (0.838, 432, 0.283, 202, 135, 210),
    MaterialKind.V_ALLOY: (2.213, 260, 0.358, 231, 200, 390),
    MaterialKind.EH: (0.0, 1650, 0.0, 525, 660, 800),
    MaterialKind.IF: (0.505, 1013, 0.271, 237, 500, 615),
    MaterialKind.NT: (0.0, 1450, 0.0, 468, 650, 900),
    MaterialKind.NV_NITRIDED: (0.0, 1217, 0.0, 432, 450, 650),
    MaterialKind.NV_NITROCARBURIZED: (0.0, 950, 0.0, 388, 450, 650),
}


@pytest.mark.parametrize("kind", list(FYP_ME))
def test_me_rows_agree_with_the_second_transcription(kind):
    row = next(r for r in ISO_6336_5_TABLE if r.kind is kind and r.quality is Quality.ME)
    a_h, b_h, a_f, b_f, lo, hi = FYP_ME[kind]
    assert (row.a_h, row.b_h, row.a_f, row.b_f) == (a_h, b_h, a_f, b_f)
    assert row.h_range == (lo, hi) and row.f_range == (lo, hi)
    assert row.checked  # the row says it was cross-checked


def test_case_hardened_mq_agrees_with_the_kisssoft_reports():
    m = iso_material("Eh", "MQ", 720)
    assert (m.sigma_h_lim, m.sigma_f_lim, m.sigma_fe) == (1500.0, 430.0, 860.0)
    assert m.source.value == "iso" and "ISO 6336-5" in m.note


def test_every_row_is_complete_and_linear():
    kinds = {r.kind for r in ISO_6336_5_TABLE}
    for k in kinds:
        assert {r.quality for r in ISO_6336_5_TABLE if r.kind is k} == set(Quality), k
    for r in ISO_6336_5_TABLE:
        lo, hi = r.h_range
        m_lo, m_hi = iso_material(r.kind, r.quality, max(lo, r.f_range[0])), iso_material(r.kind, r.quality, min(hi, r.f_range[1]))
        assert m_lo.sigma_h_lim <= m_hi.sigma_h_lim and m_lo.sigma_f_lim <= m_hi.sigma_f_lim
        # ML <= MQ <= ME at the same hardness, where the ranges overlap
    for k in kinds:
        rows = {r.quality: r for r in ISO_6336_5_TABLE if r.kind is k}
        x = max(r.h_range[0] for r in rows.values())
        s = [iso_material(k, q, x) for q in (Quality.ML, Quality.MQ, Quality.ME)]
        assert s[0].sigma_h_lim <= s[1].sigma_h_lim <= s[2].sigma_h_lim, k
        assert s[0].sigma_f_lim <= s[1].sigma_f_lim <= s[2].sigma_f_lim, k


@pytest.mark.parametrize("args,key", [
    (("Eh", "MQ", 500.0), "hardness (HV10, Eh MQ, contact)"),
    (("Eh", "MX", 700.0), "material.quality"),
    (("Unobtainium", "MQ", 700.0), "material.kind"),
    (("GTS (perl.)", "MQ", 200.0), "material"),  # a kind the table does not hold
])
def test_not_in_the_table_raises_a_one_line_error(args, key):
    with pytest.raises(RatingInputError) as e:
        iso_material(*args)
    assert e.value.key == key and isinstance(e.value, ValueError)
    assert "\n" not in str(e.value) and e.value.valid
