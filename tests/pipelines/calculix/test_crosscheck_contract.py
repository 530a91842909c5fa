"""``gearfe crosscheck`` keeps the command line's contract on every failure path (issue 24, item 4).

No real CalculiX is needed: the folder is a small fabricated one (the checks run before ccx starts), and
where ccx must run, a stand-in ``ccx`` script on PATH writes a damaged ``job.frd`` or sleeps until it is
stopped (its pid in a file, to check that no process is left running). Each failure must be one error line,
exit status 2 (143 on SIGTERM), nothing left in the folder, no ccx left running.
"""

import dataclasses
import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from pipelines.calculix.crosscheck import Quantities, load_gearfe
from pipelines.cli import main

FILES = ["crosscheck_gearfe.json", "crosscheck_ref.npz", "job.inp"]


@pytest.fixture
def folder(tmp_path):
    d = tmp_path / "run"
    d.mkdir()
    (d / "job.inp").write_text("*HEADING\nstand-in\n")
    np.savez(d / "crosscheck_ref.npz", points=np.zeros((4, 3)), pair_names=np.array(["a-b"]), pair_slave=np.array(["S"]),
             pair_master=np.array(["M"]), bodies=np.array(["a", "b"]))
    q = {f.name: 0.0 for f in dataclasses.fields(Quantities)}
    q.update(solver="gearfe", pair_force_n={}, load_share={}, max_von_mises_mpa={})
    (d / "crosscheck_gearfe.json").write_text(json.dumps(q))
    load_gearfe(d)  # a readable record: the folder's checks pass and the run reaches ccx
    return d


def _fake_ccx(tmp_path, body: str):
    bin_ = tmp_path / "bin"
    bin_.mkdir()
    exe = bin_ / "ccx"
    exe.write_text("#!/bin/sh\n" + body)
    exe.chmod(0o755)
    return bin_


def _one_error(capsys, start):
    err = [line for line in capsys.readouterr().err.splitlines() if not line.startswith("gearfe crosscheck: running")]
    assert len(err) == 1 and err[0].startswith(start), err
    return err[0]


@pytest.mark.parametrize("t", ["0", "-5", "nan", "inf", "1e9"])
def test_timeout_validated(folder, capsys, t):
    assert main(["crosscheck", str(folder), f"--timeout={t}"]) == 2
    _one_error(capsys, "gearfe crosscheck: error: --timeout = ")
    assert sorted(p.name for p in folder.iterdir()) == FILES


@pytest.mark.parametrize("damage,names", [
    (lambda d: (d / "crosscheck_ref.npz").write_bytes(b"not a zip"), "crosscheck_ref.npz is damaged"),
    (lambda d: (d / "crosscheck_gearfe.json").unlink(), "crosscheck_gearfe.json is missing or damaged"),
    (lambda d: (d / "crosscheck_gearfe.json").write_text("{"), "crosscheck_gearfe.json is missing or damaged"),
    (lambda d: (d / "crosscheck_gearfe.json").write_text("{}"), "crosscheck_gearfe.json is missing or damaged"),
    (lambda d: (d / "ccx").write_text(""), "ccx is a file"),
    (lambda d: (d / "job.inp").unlink(), "job.inp, crosscheck_ref.npz"),
])
def test_damaged_folder_is_one_line(folder, capsys, damage, names):
    damage(folder)
    before = sorted(p.name for p in folder.iterdir())
    assert main(["crosscheck", str(folder)]) == 2
    assert names in _one_error(capsys, "gearfe crosscheck: error: DIR = ")
    assert sorted(p.name for p in folder.iterdir()) == before


def test_damaged_frd_leaves_nothing(folder, tmp_path, capsys, monkeypatch):
    bin_ = _fake_ccx(tmp_path, 'printf "  100CL  101 garbage\\n" > job.frd\n: > job.dat\necho "Job finished"\n')
    monkeypatch.setenv("PATH", f"{bin_}{os.pathsep}{os.environ['PATH']}")
    assert main(["crosscheck", str(folder)]) == 2
    assert "job.frd" in _one_error(capsys, "gearfe crosscheck: error: ")
    assert sorted(p.name for p in folder.iterdir()) == FILES  # no DIR/ccx, no temporary folder


def test_sigterm_stops_ccx_and_leaves_nothing(folder, tmp_path):
    pidfile = tmp_path / "ccx.pid"
    bin_ = _fake_ccx(tmp_path, f'echo $$ > {pidfile}\nexec sleep 60\n')
    env = {**os.environ, "PATH": f"{bin_}{os.pathsep}{os.environ['PATH']}"}
    p = subprocess.Popen([sys.executable, "-m", "pipelines.cli", "crosscheck", str(folder)], env=env,
                         stderr=subprocess.PIPE, text=True)
    t0 = time.monotonic()
    while not pidfile.exists() or not pidfile.read_text().strip():
        assert time.monotonic() - t0 < 60 and p.poll() is None, "ccx stand-in did not start"
        time.sleep(0.05)
    ccx_pid = int(pidfile.read_text())
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=30)
    assert p.returncode == 143, err
    assert err.strip().splitlines()[-1] == "gearfe crosscheck: terminated (SIGTERM); no partial results left"
    with pytest.raises(ProcessLookupError):  # stopped and reaped: no orphan
        os.kill(ccx_pid, 0)
    assert sorted(q.name for q in folder.iterdir()) == FILES
