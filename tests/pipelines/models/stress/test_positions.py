"""tca.pair.te: contact at any angle of aligned involute pairs (ties of conjugate flanks) and named positions.

Independent truth: the involute's line of action. An aligned involute pair touches on the line
through the pitch point C = (r_w1, 0, 0) tangent to both base circles, at distance
t = sqrt(r^2 - r_b1^2) from T1 for a contact point at radius r, and single tooth contact lies
between B = E - p_bt and D = A + p_bt (ISO 6336-2); the TCA contact points are compared with those.
"""

import math

import numpy as np
import pytest

from pipelines.cases.reader import CASES_DIR, load_case
from pipelines.cases.stress import read_stress_case
from pipelines.models.stress.scene import pair_scene
from tca.errors import InputError
from tca.pair.analysis import run_pair_tca
from tca.pair.te import mesh_contact, path_of_contact, path_angle, position_angle


@pytest.fixture(scope="module", params=["stress_spur_pair", "stress_helical_pair"])
def drive(request):
    c = read_stress_case(load_case(CASES_DIR / f"{request.param}.toml"))
    return request.param, c, run_pair_tca(c.pair, c.tca)


def _t(path, point) -> float:
    """Distance from T1 along the line of action of a contact point at mid-face [mm]."""
    return math.sqrt(point[0] ** 2 + point[1] ** 2 - path.r_b1 ** 2)


def test_named_positions_touch_where_iso_puts_them(drive):
    name, c, r = drive
    path = path_of_contact(c.pair)
    g1 = c.pair.gear1
    # closed forms of the standard-centre-distance pair: alpha_wt = alpha_t, t_C = r_b1 tan alpha_t
    assert path.alpha_wt == pytest.approx(g1.transverse_pressure_angle, abs=1e-12)
    assert path.t_c == pytest.approx(g1.r_b * math.tan(g1.transverse_pressure_angle), rel=1e-12)
    assert 1.5 < path.contact_ratio < 1.7
    for pos in ("pitch", "hpstc", "lpstc"):
        mc = mesh_contact(r, position_angle(r, pos))
        assert mc.k == 0 and mc.tied == ()  # the reference pair, alone: single tooth contact
        assert abs(mc.point[2]) < 0.05  # at mid-face (the TCA point of a line contact)
        # a helical contact line moves by z tan(beta_b) along the line of action per axial offset z of the point
        assert _t(path, mc.point) == pytest.approx(path.t(pos), abs=2e-3 + abs(mc.point[2]) * 0.2)
    # the roll angle of the pitch point is tan(alpha_wt)
    assert position_angle(r, roll=math.tan(path.alpha_wt)) == pytest.approx(position_angle(r, "pitch"), abs=1e-12)


def test_a_cycle_of_angles_builds_every_scene(drive):
    """>= 40 angles over one mesh cycle: every scene builds; spur: two pairs (tied TE) exactly in the double zones."""
    name, c, r = drive
    path = path_of_contact(c.pair)
    phi_c = path.phi1(path.t_c)
    angles = phi_c + np.linspace(0.0, c.pair.gear1.pitch_angle, 41)[:-1] + 1e-4  # off the grid too
    doubles = 0
    for phi in np.concatenate([angles, np.asarray(r.phi1[:-1])]):
        sc = pair_scene(c.pair, r, float(phi), c.torque, c.mesh, c.fe.material)
        itf = sc.interfaces[0]
        assert itf.hertz.line and itf.hertz.b > 0
        mc = itf.contact
        if name == "stress_spur_pair":
            t_pair = _t(path, mc.point)
            # one TCA grid step along the line of action: the TCA brackets a change of pair to within it
            step = path.r_b1 * c.pair.gear1.pitch_angle / c.tca.steps_per_cycle
            assert path.t_a - 1e-3 <= t_pair <= path.t_e + 1e-3
            if path.t_b + step < t_pair < path.t_d - step:
                assert mc.tied == ()
            elif path.t_a + step < t_pair < path.t_b - step or path.t_d + step < t_pair < path.t_e - step:
                assert len(mc.tied) == 1
                doubles += 1
    if name == "stress_spur_pair":
        assert doubles >= 30  # eps_alpha = 1.57: 57 % of the cycle in double contact (80 angles)


def test_positions_off_the_path_are_input_errors(drive):
    _, c, r = drive
    with pytest.raises(InputError, match="roll_deg"):
        path_angle(c.pair, None, math.radians(1.0))
    with pytest.raises(InputError, match="roll_deg"):
        path_angle(c.pair, None, math.radians(80.0))
    with pytest.raises(InputError, match="position"):
        path_angle(c.pair, "tip")


def test_shifted_spur_pair_of_the_issue_runs_at_every_angle():
    """16/24 teeth with profile shifts +0.2/-0.2 (issue 12): every angle of a cycle builds its scene."""
    t = load_case(CASES_DIR / "stress_spur_pair.toml")
    t.data["gears"]["pinion"].update(teeth=16, profile_shift=0.2)
    t.data["gears"]["wheel"].update(profile_shift=-0.2)
    c = read_stress_case(t)
    r = run_pair_tca(c.pair, c.tca)
    path = path_of_contact(c.pair)
    assert path.contact_ratio > 1.2
    for pos in ("pitch", "hpstc", "lpstc"):
        mc = mesh_contact(r, position_angle(r, pos))
        assert _t(path, mc.point) == pytest.approx(path.t(pos), abs=2e-3)
    for phi in path.phi1(path.t_c) + np.linspace(0.0, c.pair.gear1.pitch_angle, 41)[:-1]:
        sc = pair_scene(c.pair, r, float(phi), c.torque, c.mesh, c.fe.material)
        assert sc.interfaces[0].hertz.line


def test_next_pair_at_the_hpstc_touches_unless_its_tip_is_relieved():
    """At the HPSTC the entering pair meets the wheel's tip: a gap of 0 for unmodified flanks, C_a with a relief.

    Independent truth: the relief's amount at the tip circle (15 um, pipelines/cases/stress_spur_pair_relief.toml);
    measured 15.25 um (the rack's normal relief mapped onto the involute, within 3 %, tests/tca/geometry/test_modifications.py).
    """
    from dataclasses import replace

    from pipelines.models.stress.run import build_scene

    plain = read_stress_case(load_case(CASES_DIR / "stress_spur_pair.toml"))
    relief = read_stress_case(load_case(CASES_DIR / "stress_spur_pair_relief.toml"))
    assert build_scene(replace(plain, position="hpstc"))[0].info["next_pair_gap_um"] == pytest.approx(0.0, abs=1e-6)
    assert build_scene(replace(plain, position="pitch"))[0].info["next_pair_gap_um"] == math.inf
    gap = build_scene(replace(relief, position="hpstc"))[0].info["next_pair_gap_um"]
    assert gap == pytest.approx(relief.pair.gear2.tip_relief.amount * 1e3, rel=0.03)
