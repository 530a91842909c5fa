"""gearfe against CalculiX on the same scene: run ccx on DIR/job.inp and tabulate both solvers.

``gearfe crosscheck DIR`` takes a folder written by ``gearfe stress CASE --out DIR --inp`` (or
``gearfe run ... --inp``), runs ``ccx`` on a copy of ``job.inp`` in ``DIR/ccx`` and writes
``DIR/crosscheck.md`` (a side-by-side table: contact force, reaction torque, load share per tooth
pair, maximum von Mises per body, fillet maximum principal stress, peak contact pressure, maximum
displacement, wall time and peak memory of both solvers, with the differences and the issue's
targets) and ``DIR/crosscheck.json`` (the same rows and both solvers' numbers). How each number is
computed: :mod:`pipelines.calculix.crosscheck`; the job's conventions: ``docs/calculix.md``.
Without CalculiX: one error line naming ``apt-get install calculix-ccx``, exit status 2.

The contract of every subcommand (docs/errors.md): a missing or damaged input (``job.inp``,
``crosscheck_ref.npz``, ``crosscheck_gearfe.json``, a file named ``DIR/ccx``), a bad ``--timeout``, ccx's
own failure, a damaged ``job.frd`` or the time limit are one error line with exit status 2; ccx runs in
a temporary folder that replaces ``DIR/ccx`` only on success, so no failure leaves anything behind; SIGINT
and SIGTERM stop ccx (SIGTERM, then SIGKILL after 5 s) before gearfe exits 130 / 143. A progress line every
10 s while ccx runs.
"""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import asdict
from pathlib import Path

from pipelines.calculix.job import MAX_TIMEOUT_S, ccx_path, check_timeout
from pipelines.calculix.crosscheck import check_folder, crosscheck, table
from pipelines.cli.interrupt import check_interrupted

__all__ = ["add_args", "handle"]


def add_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("dir", help="folder written by 'gearfe stress CASE --out DIR --inp'")
    p.add_argument("--timeout", type=float, default=3600.0, help=f"time limit of the ccx run [s], in (0, {MAX_TIMEOUT_S:g}] (default 3600)")


def _progress(wall_s: float, peak_mb: float) -> None:
    check_interrupted()
    print(f"gearfe crosscheck: ccx running, {wall_s:.0f} s, peak memory {peak_mb:.0f} MB", file=sys.stderr, flush=True)


def handle(args) -> int:
    folder = Path(args.dir)
    check_timeout(args.timeout)
    check_folder(folder)  # bad folder: one line, exit 2, before any work
    ccx_path()  # no CalculiX: one line naming the install command, exit 2
    print(f"gearfe crosscheck: running ccx on {folder}/job.inp (time limit {args.timeout:g} s)", file=sys.stderr, flush=True)
    g, c = crosscheck(folder, timeout=args.timeout, progress=_progress)
    md, rows = table(g, c)
    head = (f"# gearfe vs CalculiX: {folder}\n\nSame mesh, supports, torque and penalty (job.inp); "
            "differences relative to gearfe (load shares: absolute; cost: ratio CalculiX / gearfe).\n\n")
    (folder / "crosscheck.md").write_text(head + md)
    (folder / "crosscheck.json").write_text(json.dumps({"rows": rows, "gearfe": asdict(g), "calculix": asdict(c)}, indent=2) + "\n")
    print(md, end="")
    print(f"results in {folder}/crosscheck.md, crosscheck.json (ccx files in {folder}/ccx/)")
    return 0
