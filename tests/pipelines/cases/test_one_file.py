"""One case file per pair (issue 24, item 7): every command takes the same pair file; the torque names its gear."""

import json

import pytest

from tca.errors import InputError

from pipelines.cases.kinds import read_case, validate_case
from pipelines.cases.reader import load_case
from pipelines.cases.stress import torque_record
from pipelines.cli import main

from tests.support.shipped import shipped_data, write_case

STRESS = "pipelines/cases/stress_spur_pair.toml"  # 19/24 teeth, torque_nm = 120 on the wheel


def pair_file(tmp_path, **over):
    """The shipped spur stress case as a pair file (kind = "pair", no model key) with overrides."""
    data = shipped_data(STRESS, {"kind": "pair", "model": None, "torque_nm": None, **over})
    return write_case(tmp_path, "pair", data)


@pytest.mark.parametrize("command", ["stress", "run", "compare", "ltca"])
def test_pair_file_with_a_driver_torque_is_read_by_every_stress_command(tmp_path, command):
    _, got = read_case(pair_file(tmp_path, driver_torque_nm=95.0), command)
    case = got[0] if command == "ltca" else got
    assert case.model == "pair"
    assert case.torque == pytest.approx(95e3 * 24 / 19, rel=1e-12)  # [N mm] on the driven wheel, no losses
    rec = torque_record(case)
    assert rec["torque_gear"] == "wheel" and rec["driver_gear"] == "pinion"
    assert rec["driver_torque_nm"] == pytest.approx(95.0, rel=1e-12)


@pytest.mark.parametrize("key", ["torque_nm", "driven_torque_nm"])
def test_torque_nm_is_the_driven_gears(tmp_path, key):
    _, case = read_case(pair_file(tmp_path, **{key: 120.0}), "stress")
    assert case.torque == 120e3 and torque_record(case)["driven_torque_nm"] == 120.0


def test_two_torques_refused(tmp_path):
    with pytest.raises(InputError) as e:
        read_case(pair_file(tmp_path, driver_torque_nm=95.0, torque_nm=120.0), "stress")
    assert e.value.field == "driver_torque_nm" and "exactly one of" in str(e.value)


def test_a_stress_command_needs_a_torque_a_tca_does_not(tmp_path):
    f = pair_file(tmp_path, position=None)
    with pytest.raises(InputError) as e:
        read_case(f, "stress")
    assert e.value.field == "driven_torque_nm" and "missing" in str(e.value)
    validate_case(load_case(f), "tca")


def test_torque_in_newton_millimetres_is_named(tmp_path):
    with pytest.raises(InputError) as e:
        read_case(pair_file(tmp_path, torque_nm=120000.0), "stress")
    assert e.value.field == "torque_nm" and "looks like N mm: 120 N m?" in str(e.value)


def test_stress_files_run_through_gearfe_tca(tmp_path):
    validate_case(load_case("pipelines/cases/ltca_pair_small.toml"), "tca")  # [ltca] checked, not planned
    with pytest.raises(InputError) as e:
        validate_case(load_case("pipelines/cases/stress_part1_new.toml"), "tca")
    assert e.value.field == "model" and "planetary" in str(e.value)
    out = tmp_path / "out"
    assert main(["tca", STRESS, "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["driver"] == "pinion" and s["center_distance_mm"] == pytest.approx(0.5 * 4.5 * 43)


@pytest.mark.parametrize("face,c_max_um", [(40.0, 1000.0), (10.0, 62.5)])
def test_documented_crowning_maximum_builds_its_surface(tmp_path, face, c_max_um):
    # issue 24: a lead crowning at its documented maximum failed later ("Chebyshev fit ... did not converge"); the
    # maximum is now min(s_n / 4, (b/2)^2 / (4 r_D)): 2 a_pl r_D <= 0.5 (r_D = 100 mm), and one above it is refused
    data = shipped_data("pipelines/cases/stress_helical_crowned.toml", {"gears.pinion.face_width_mm": face,
                                                                         "gears.wheel.face_width_mm": face})
    data["gears"]["pinion"]["crowning"]["c_beta_um"] = c_max_um
    _, case = read_case(write_case(tmp_path, "max", data), "stress")
    g = case.pair.gear1
    for side in (1, -1):
        assert g.surface(side).fit_error < 1e-9  # the crowned flank's Chebyshev fit at its tolerance
    data["gears"]["pinion"]["crowning"]["c_beta_um"] = c_max_um + 0.2
    with pytest.raises(InputError) as e:
        read_case(write_case(tmp_path, "above", data), "stress")
    assert e.value.field == "gears.pinion.crowning.c_beta_um" and f"<= {c_max_um:g}" in str(e.value)
