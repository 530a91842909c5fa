"""Hostile files and sweeps (issue 24, item 5): one line, exit status 2, nothing written; [positions]-only sweeps."""

import os

import pytest

from pipelines.cli import main
from pipelines.cli.sweep import build_grid
from tests.pipelines.cli.test_tca import FAST_PAIR

DEEP = {
    "arrays": "a = " + "[" * 5000 + "]" * 5000 + "\n",
    "inline tables": "a = " + "{b = " * 3000 + "1" + "}" * 3000 + "\n",
    "dotted tables": "[" + ".".join(["a"] * 3000) + "]\nx = 1\n",
}


@pytest.mark.parametrize("name", list(DEEP))
def test_deeply_nested_file_refused(tmp_path, capsys, name):
    f = tmp_path / "deep.toml"
    f.write_text(DEEP[name])
    out = tmp_path / "out"
    assert main(["tca", str(f), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "nested at most 16 levels deep" in err[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["deep.toml"]


def test_out_name_too_long_refused_before_work(tmp_path, capsys):
    f = tmp_path / "pair.toml"
    f.write_text(FAST_PAIR)
    name_max = os.pathconf(tmp_path, "PC_NAME_MAX")
    out = tmp_path / "new" / ("x" * (name_max + 1))
    assert main(["tca", str(f), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("gearfe tca: error: --out = ") and f"at most {name_max} bytes" in err[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pair.toml"]  # no parent folder left
    # the longest name the file system takes runs (the staging folder's name is shortened)
    out = tmp_path / ("y" * name_max)
    assert main(["tca", str(f), "--out", str(out)]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pair.toml", out.name]


SWEEP = 'task = "tca"\nbase = "base.toml"\n[[axes]]\nkey = "misalignment.d_gamma_arcmin"\nvalues = {values}\n'


def test_duplicated_grid_points_refused(tmp_path, capsys):
    (tmp_path / "base.toml").write_text(FAST_PAIR)
    (tmp_path / "sweep.toml").write_text(SWEEP.format(values="[0.0, 3.0, 0.0]"))
    out = tmp_path / "out"
    assert main(["sweep", str(tmp_path / "sweep.toml"), "--out", str(out), "--workers", "2"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "axes[0].values = 0.0 is invalid" in err[0] and "listed twice" in err[0]
    assert not out.exists()


def test_positions_only_stress_sweep_builds(tmp_path):
    base = (os.path.abspath("pipelines/cases/stress_pair_small.toml"))
    (tmp_path / "sweep.toml").write_text(f'task = "stress"\nbase = "{base}"\n[positions]\nsteps = 4\n')
    task, points, keys = build_grid(tmp_path / "sweep.toml")
    assert task == "stress" and keys == ["positions.step"] and len(points) == 4
    assert len({p["id"] for p in points}) == 4
