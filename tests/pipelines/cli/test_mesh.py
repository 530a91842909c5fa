"""`gearfe mesh CASE --out DIR`: files, summary keys, and exit status 2 with no files on bad input."""

import json

import meshio
import pytest

from pipelines.cases.reader import CASES_DIR
from pipelines.cli import main

CASE = f"""
title = "Table 3.1 pair, coarse"
pair_case = "{CASES_DIR / 'table31_sun_planet.toml'}"
position = "max_te"
[mesh]
teeth = 3
coarse_size_mm = 4.0
contact_size_mm = 1.0
{{extra}}
"""


def _case(tmp_path, text, name="case.toml"):
    p = tmp_path / name
    p.write_text(text)
    return str(p)


def test_mesh_command_writes_the_model(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["mesh", _case(tmp_path, CASE.format(extra='element_type = "C3D8I"')), "--out", str(out)]) == 0
    assert {p.name for p in out.iterdir()} == {"mesh.vtu", "mesh.inp", "mesh.msh", "summary.json"}
    s = json.loads((out / "summary.json").read_text())
    for k in ("elements", "nodes", "min_scaled_jacobian", "max_aspect_ratio", "elapsed_s"):
        assert k in s
    v = meshio.read(out / "mesh.vtu")
    assert s["elements"] == len(v.cells[0].data) and s["nodes"] == len(v.points)
    assert 0 < s["min_scaled_jacobian"] <= 1 and s["max_aspect_ratio"] >= 1
    assert s["contact_node_gap_mm"] < 1e-9
    assert s["bodies"]["sun"]["loaded_tooth"] == s["position"]["loaded_teeth"][0]
    assert "*ELEMENT, TYPE=C3D8I" in (out / "mesh.inp").read_text()
    assert "min_scaled_jacobian" in capsys.readouterr().out


def test_one_gear_without_tca(tmp_path):
    text = f'pair_case = "{CASES_DIR / "table31_sun_planet.toml"}"\ngear = "planet"\n[mesh]\nteeth = 1\ncoarse_size_mm = 4.0\n'
    out = tmp_path / "out"
    assert main(["mesh", _case(tmp_path, text), "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["gear"] == "planet" and s["bodies"]["planet"]["teeth"] == [0]


@pytest.mark.parametrize("extra,fragment", [
    ("teeth_per_gear = 3", "mesh.teeth_per_gear"),  # unknown key
    ("growth = 5.0", "mesh.growth"),
    ("rim_depth_mm = -2.0", "mesh.rim_depth_mm"),
    ("fillet_size_mm = 8.0", "mesh.fillet_size_mm"),
    ('element_type = "C3D20"', "mesh.element_type"),
])
def test_bad_mesh_input_exits_2_without_files(tmp_path, capsys, extra, fragment):
    out = tmp_path / "out"
    assert main(["mesh", _case(tmp_path, CASE.format(extra=extra)), "--out", str(out)]) == 2
    assert fragment in capsys.readouterr().err
    assert not out.exists() or not any(out.iterdir())


@pytest.mark.parametrize("edit,fragment", [
    (lambda t: t.replace('"max_te"', "5000"), "position"),
    (lambda t: t.replace('"max_te"', '"middle"'), "position"),
    (lambda t: t.replace("table31_sun_planet.toml", "nowhere.toml"), "pair_case"),
    (lambda t: t.replace("teeth = 3", "teeth = 80"), "mesh.teeth"),
])
def test_bad_case_exits_2_without_files(tmp_path, capsys, edit, fragment):
    out = tmp_path / "out"
    assert main(["mesh", _case(tmp_path, edit(CASE.format(extra=""))), "--out", str(out)]) == 2
    assert fragment in capsys.readouterr().err
    assert not out.exists() or not any(out.iterdir())


def test_the_shipped_mesh_cases_parse():
    # full runs of these cases are in benchmarks.mesher; here: they exist and are read strictly
    from pipelines.cases.reader import load_case

    for p in sorted(CASES_DIR.glob("mesh_*.toml")):
        c = load_case(p)
        assert c.has("mesh")
