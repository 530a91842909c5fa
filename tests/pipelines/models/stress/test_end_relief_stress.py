"""End relief through `gearfe stress`: the aligned spur pair with and without a linear end relief.

Case: pipelines/cases/stress_spur_pair_end_relief.toml (the 19/24 spur pair of stress_spur_pair.toml,
15 um over 3 mm at both face ends of both gears), coarse (refine 0.3, one tooth per gear, 9.9k / 12.2k DOF; was
refine 0.5, 21k DOF: the test checks a behaviour, the face ends unloaded and unflagged).
Independent truth: the total normal force T2 / r_b2 (statics) and the relief's geometry (beyond the
relief start the flanks are apart by 2 C(z) before load, more than the elastic approach near the face
ends); the pressure at the face ends of the unmodified pair is a regression pin of the same model.
"""

from dataclasses import replace

import numpy as np
import pytest

from pipelines.cases.reader import CASES_DIR, load_case
from pipelines.cli import main
from pipelines.cases.stress import read_stress_case
from pipelines.models.stress.run import run_stress


def _run(name, tmp_path):
    c = read_stress_case(load_case(CASES_DIR / name))
    c = replace(c, mesh=replace(c.mesh, teeth=1, refine=0.3))
    run = run_stress(c, tmp_path / name)
    p = np.nan_to_num(run.result.contact_pressure)
    z = run.mesh.points[:, 2]
    b = c.pair.gear1.face_width
    mid = p[(p > 0) & (np.abs(z) <= 0.25 * b)].max()
    ends = p[np.abs(np.abs(z) - 0.5 * b) < 1e-9].max()
    return c, run.summary, mid, ends


def test_end_relief_unloads_the_face_ends(tmp_path):
    c0, s0, mid0, ends0 = _run("stress_spur_pair.toml", tmp_path)
    c1, s1, mid1, ends1 = _run("stress_spur_pair_end_relief.toml", tmp_path)
    force = c0.torque / c0.pair.gear2.r_b
    assert s0["contact_force_n"] == pytest.approx(force, rel=0.005)
    assert s1["contact_force_n"] == pytest.approx(force, rel=0.005)
    # unmodified line contact: the face ends carry about the mid-face pressure (measured 0.98 at this
    # coarse mesh, refine 0.3, and 0.97 at refine 0.5; regression pin) and the summary flags the edge contact
    assert ends0 > 0.9 * mid0 and s0["fe_edge_contact"]
    # relieved by 30 um (both gears) at the ends: no pressure there, no edge flag, the load moved inside
    # (measured at refine 0.3: ends 0.0, mid-face 1145 against 936 MPa unrelieved)
    assert ends1 < 0.05 * mid1 and not s1["fe_edge_contact"]
    assert mid1 > mid0


@pytest.mark.parametrize("key, value", [("amount_um", 0.0), ("amount_um", 2000.0), ("length_mm", 7.5),
                                        ("length_mm", 0.0), ("shape", '"cubic"'), ("ends", '"middle"')])
def test_a_bad_end_relief_exits_2_without_files(tmp_path, key, value, capsys):
    text = (CASES_DIR / "stress_spur_pair_end_relief.toml").read_text()
    lines = text.splitlines()
    i = lines.index("[gears.pinion.end_relief]")
    j = next(q for q in range(i + 1, len(lines)) if lines[q].startswith(key))
    lines[j] = f"{key} = {value}"
    path = tmp_path / "bad.toml"
    path.write_text("\n".join(lines) + "\n")
    out = tmp_path / "out"
    assert main(["stress", str(path), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"gears.pinion.end_relief.{key}" in err[0]
    assert not out.exists()


def test_gearfe_tca_on_a_misaligned_helical_pair_with_mixed_reliefs(tmp_path):
    """Linear relief on the sun, parabolic on the planet, Δγ = 3' (Table 1.1 involute pair): the ridge of the
    sun touches first (an edge contact), no traceback, files written; the relief lowers the TE of the
    unmodified pair's face-end edge contact (77.8..82.4 arcsec, pipelines/cases/part1_sun_planet_involute.toml).
    One cycle of 8 steps (was 16): every TE of the unmodified pair is above 77.8 arcsec, so any sample of the
    relieved one below 77 still tells them apart; measured te_max 56.0 arcsec at 8 steps."""
    import json

    text = (CASES_DIR / "part1_sun_planet_involute.toml").read_text()
    text = text.replace("[gears.planet]", "[gears.sun.end_relief]\namount_um = 12.0\nlength_mm = 5.0\n\n[gears.planet]")
    text = text.replace("[misalignment]", '[gears.planet.end_relief]\namount_um = 12.0\nlength_mm = 5.0\n'
                        'shape = "parabolic"\n\n[misalignment]')
    text = text.replace("cycles = 2\nsteps_per_cycle = 40", "cycles = 1\nsteps_per_cycle = 8")
    path = tmp_path / "relieved.toml"
    path.write_text(text)
    out = tmp_path / "out"
    assert main(["tca", str(path), "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["te_max_arcsec"] < 77.0 and s["edge_contact"]
