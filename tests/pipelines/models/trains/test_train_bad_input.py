"""Bad input of a train's loaded TCA found before any work: a pin error that takes a planet out of both meshes
(docs/trains.md, Eq. D2) and flank models above GEARFE_MAX_MEMORY_GB (Eq. P3): one line, exit 2, no files."""

import math

import pytest

from tca.errors import InputError
from tca.geometry.gear import Gear

from pipelines.cli import main
from pipelines.models.trains.depth import check_pin_errors, depth_range
from tests.support.shipped import shipped_table, write_case


def small(m):
    d = math.radians
    return (Gear("sun", 24, m, d(20), 5 * m), Gear("planet", 21, m, d(20), 5 * m),
            Gear("ring", 66, m, d(20), 5 * m, internal=True, addendum=0.95))


def test_pin_error_range_from_the_tip_root_clearances():
    """Standard gears (x = 0), tool addendum 1.25 m, addendum 1 m: the tips clear the mates' roots while the planet's
    axis stays within c* m = 0.25 m of E (Eq. D3, hand count: sun tip r1 + m against planet root r2 - 1.25 m); the
    planet's depth in both meshes (Eq. D2) allows far more. Inside, a pin error is valid; beyond, bad input."""
    sun, planet, ring = small(2.0)
    r = depth_range(sun, planet, ring)
    assert r.radial_range() == pytest.approx((-0.5, 0.5), abs=1e-12)
    check_pin_errors(r, [(-0.49, 0.0), (0.49, 0.0), (0.0, 0.05)], lambda i: "pin")
    with pytest.raises(InputError, match=r"pin = 510\.0 .*\(-500\.0, 500\.0\) um \(planet 2's axis .* planet tip / ring root"):
        check_pin_errors(r, [(0.0, 0.0), (0.51, 0.0)], lambda i: "pin")
    with pytest.raises(InputError, match="sun tip / planet root"):
        check_pin_errors(r, [(-0.51, 0.0)], lambda i: "pin")


def _cli_refuses(tmp_path, capsys, data, key, env=None, monkeypatch=None):
    case = write_case(tmp_path, "bad", data)
    out = tmp_path / "out"
    assert main(["ltca", str(case), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and key in err[0], err
    assert not out.exists()
    return err[0]


def test_pin_error_out_of_both_meshes_exit_2(tmp_path, capsys):
    """Table 3.1 (m = 4 mm): a radial pin error of 1000 um puts planet 2's tips on the ring's roots (range +-1000 um);
    refused before any work, naming the key, the value and the range."""
    t = shipped_table("part3_indexing", {"train.planet_errors": [{"planet": 1, "tangential_um": 20.0},
                                                                 {"planet": 2, "radial_um": 1000.0}]})
    line = _cli_refuses(tmp_path, capsys, t.data, "train.planet_errors[1].radial_um = 1000")
    assert "(-1000.0, 1000.0) um" in line and "planet 2" in line


def test_memory_limit_before_the_build_exit_2(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("GEARFE_MAX_MEMORY_GB", "0.6")  # the default grid needs about 0.82 GB (Eq. P3)
    _cli_refuses(tmp_path, capsys, shipped_table("part3_indexing").data, "ltca.teeth = 3")
    monkeypatch.setenv("GEARFE_MAX_MEMORY_GB", "10")
    fine = shipped_table("part3_indexing", {"ltca.profile_size_mm": 0.05, "ltca.axial_size_mm": 1.0})
    _cli_refuses(tmp_path, capsys, fine.data, "ltca.profile_size_mm = 0.05")
