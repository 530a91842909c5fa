"""The command line on a user's own pairs (issue 24): an impossible pair is one error line, exit status 2 and no
files; a shifted pair without ``center_distance_mm`` runs at its zero-backlash centre distance with TE = 0."""

import json
import math

import pytest

from pipelines.cli import main

PAIR = """kind = "pair"
driver = "p"
driven = "w"
{extra}
[gears.p]
teeth = {z1}
module_mm = 5.0
pressure_angle_deg = 20.0
face_width_mm = 30.0
profile_shift = {x1}
[gears.w]
teeth = 52
module_mm = {m2}
pressure_angle_deg = {a2}
face_width_mm = 30.0
profile_shift = 0.3
[tca]
cycles = 1
steps_per_cycle = 10
"""


def case(tmp_path, extra="", z1=17, x1=0.3, m2=5.0, a2=20.0):
    p = tmp_path / "case.toml"
    p.write_text(PAIR.format(extra=extra, z1=z1, x1=x1, m2=m2, a2=a2))
    return p


@pytest.mark.parametrize("kw,key", [
    (dict(m2=4.5), "gears.w.module_mm = 4.5"),
    (dict(a2=25.0), "gears.w.pressure_angle_deg = 25.0"),
    (dict(extra="center_distance_mm = 172.5"), "center_distance_mm = 172.5"),  # the standard one: teeth overlap
])
def test_impossible_pair_refused_without_files(tmp_path, capsys, kw, key):
    out = tmp_path / "out"
    assert main(["tca", str(case(tmp_path, **kw)), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"gearfe tca: error: {key} is invalid")
    assert not out.exists()


def test_shifted_pair_runs_at_its_operating_centre_distance(tmp_path):
    out = tmp_path / "out"
    assert main(["tca", str(case(tmp_path)), "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    inv = lambda a: math.tan(a) - a  # noqa: E731
    al = math.radians(20)
    target = 2 * math.tan(al) * 0.6 / 69 + inv(al)
    lo, hi = 0.1, 1.0
    for _ in range(100):  # bisection of inv alpha_w
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if inv(mid) < target else (lo, mid)
    a_w = 0.5 * 5.0 * 69 * math.cos(al) / math.cos(lo)
    assert s["center_distance_mm"] == pytest.approx(a_w, abs=1e-9) and s["center_distance_source"] == "zero backlash"
    assert abs(s["te_peak_to_peak_arcsec"]) < 1e-6  # conjugate involutes at zero backlash
