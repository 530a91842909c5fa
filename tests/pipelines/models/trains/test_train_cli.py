"""gearfe ltca of train cases: bad input (one line, exit 2, no files) and a short run of a shipped Part 3 case."""

import json

import pytest

from tca.errors import GeometryError, InputError

from pipelines.cli import main
from pipelines.cases.kinds import KINDS, read_checked
from pipelines.cases.trains import read_planetary_ltca

from tests.support.shipped import shipped_table, write_case

COARSE = {"profile_size_mm": 2.0, "axial_size_mm": 8.0, "slice_mm": 4.0}


def read_isostatic(t):
    """The isostatic reader of gearfe ltca as the command line calls it (the case file's key names)."""
    return read_checked(t, KINDS["isostatic"], "ltca")


@pytest.mark.parametrize("overrides, key", [
    ({"train.planets": 5}, "train.planets"),  # 216 / 5 is not an integer
    ({"ltca.pin_stiffness_n_per_um": 0.0}, "ltca.pin_stiffness_n_per_um"),
    ({"ltca.sun_support_n_per_um": -1.0}, "ltca.sun_support_n_per_um"),
    ({"ltca.sun_support_n_per_um": 100.0}, "ltca.sun_support_n_per_um"),  # the sun floats in the case
    ({"train.carrier_axis": "floating", "train.sun_axis": "fixed"}, "train.carrier_axis"),
    ({"ltca.positions_per_cycle": 0}, "ltca.positions_per_cycle"),
    ({"ltca.torques_nm": [-5.0]}, "ltca.torques_nm"),
    ({"ltca.teeth": 4}, "ltca.teeth"),
])
def test_bad_isostatic_ltca_keys(overrides, key):
    with pytest.raises(InputError, match=key.replace(".", r"\.")):
        read_isostatic(shipped_table("part3_indexing", overrides))


def test_colliding_planets_are_bad_input():
    """Eight planets of 43 teeth around a sun of 65 (216 / 8 = 27): the tip circles of neighbours overlap."""
    with pytest.raises((InputError, GeometryError), match="overlap|collide"):
        read_isostatic(shipped_table("part3_ideal", {"train.planets": 8}))


def test_planetary_case_reads_with_default_torque():
    c = read_planetary_ltca(shipped_table("part1_planetary_regulation"))
    assert c.kind == "planetary" and c.planets == 5 and c.opts.regulation == "tca"
    assert c.opts.torques[0] == pytest.approx(5 * 2 * 200.0 * 30.0 * c.sun.r_p)
    c = read_planetary_ltca(shipped_table("part1_twin_dgamma", {"ltca.regulation": "none"}))
    assert c.opts.regulation == "none"


def test_cli_bad_input_exit_2_no_files(tmp_path, capsys):
    case = write_case(tmp_path, "bad", shipped_table("part3_indexing", {"ltca.pin_stiffness_n_per_um": -3.0}).data)
    out = tmp_path / "out"
    assert main(["ltca", str(case), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "ltca.pin_stiffness_n_per_um" in err and len(err.strip().splitlines()) == 1
    assert not out.exists()


def test_cli_part3_indexing_run(tmp_path):
    """The shipped indexing case (floating sun, 20 um), a few positions: K_gamma near 1, files, conventions."""
    ltca = {**COARSE, "positions_per_cycle": 1, "carrier_revolutions": 2.0 / 151, "torques_nm": [3000.0, 1500.0]}
    case = write_case(tmp_path, "c", shipped_table("part3_indexing", {"ltca": ltca}).data)
    out = tmp_path / "out"
    assert main(["ltca", str(case), "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    for f in ("results.csv", "planet_shares.png", "te_train.png", "sun_center.png", "report.html", "summary.json"):
        assert (out / f).is_file() and f in s["files"]
    assert s["positions"] == 2 and s["planets"] == 3 and s["sun_axis"] == "floating"
    assert s["k_gamma"] == pytest.approx(1.0, abs=0.01)
    assert len(s["planet_shares"]) == 3 and set(s["planet_shares"][0]) >= {"sun_min", "sun_mean", "sun_max"}
    assert "torque" in s["conventions"] and "k_gamma" in s["conventions"]
    assert 15.0 < s["torques"][0]["sun_center_um"]["max_offset"] < 30.0  # 2 s / 3 = 25 um (Part 3, 3.4.2)
    lines = (out / "results.csv").read_text().strip().splitlines()
    assert len(lines) == 1 + 2 * 2


@pytest.mark.bench  # two model builds (~15 s): run by make bench, to keep make test within its budget
def test_cli_compare_floating_against_fixed_sun(tmp_path):
    """gearfe compare of two trains: the Part 3 indexing case with the sun floating and held, one position."""
    ltca = {**COARSE, "positions_per_cycle": 1, "carrier_revolutions": 1.0 / 151}
    a = write_case(tmp_path, "floating", shipped_table("part3_indexing", {"ltca": ltca}).data)
    b = write_case(tmp_path, "fixed", shipped_table("part3_indexing", {"ltca": ltca, "train.sun_axis": "fixed"}).data)
    out = tmp_path / "out"
    assert main(["compare", str(a), str(b), "--out", str(out)]) == 0
    s = json.loads((out / "compare.json").read_text())
    k = {r["train"]: r["k_gamma"] for r in s["rows"]}
    assert k["floating"] == pytest.approx(1.0, abs=0.01) and k["fixed"] > 1.3
    assert s["finding"].startswith("floating shares the load more evenly")
    for f in ("compare_shares.png", "report.html", "floating/planet_shares.png", "fixed/results.csv"):
        assert (out / f).is_file()


def test_cli_compare_train_with_a_pair_is_bad_input(tmp_path, capsys):
    a = write_case(tmp_path, "a", shipped_table("part3_indexing").data)
    out = tmp_path / "out"
    assert main(["compare", str(a), "pipelines/cases/stress_pair_small.toml", "--out", str(out)]) == 2
    assert "kind" in capsys.readouterr().err
    assert not out.exists()
