"""gearfe against CalculiX on the same scene: run ccx on DIR/job.inp and tabulate both solvers (issue 13).

``gearfe crosscheck DIR`` takes a folder written by ``gearfe stress CASE --out DIR --inp`` (or
``gearfe run ... --inp``), runs ``ccx`` on a copy of ``job.inp`` in ``DIR/ccx`` and writes
``DIR/crosscheck.md`` (a side-by-side table: contact force, reaction torque, load share per tooth
pair, maximum von Mises per body, fillet maximum principal stress, peak contact pressure, maximum
displacement, wall time and peak memory of both solvers, with the differences and the issue's
targets) and ``DIR/crosscheck.json`` (the same rows and both solvers' numbers). How each number is
computed: :mod:`pipelines.calculix.crosscheck`; the job's conventions: ``docs/calculix.md``.
Without CalculiX: one error line naming ``apt-get install calculix-ccx``, exit status 2.
"""

from __future__ import annotations

import argparse
import json
from dataclasses import asdict
from pathlib import Path

from pipelines.calculix.job import ccx_path
from pipelines.calculix.crosscheck import crosscheck, load_reference, table

__all__ = ["add_args", "handle"]


def add_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("dir", help="folder written by 'gearfe stress CASE --out DIR --inp'")
    p.add_argument("--timeout", type=float, default=3600.0, help="time limit of the ccx run [s] (default 3600)")


def handle(args) -> int:
    folder = Path(args.dir)
    load_reference(folder)  # bad folder: one line, exit 2, before any work
    ccx_path()  # no CalculiX: one line naming the install command, exit 2
    g, c = crosscheck(folder, timeout=args.timeout)
    md, rows = table(g, c)
    head = (f"# gearfe vs CalculiX: {folder}\n\nSame mesh, supports, torque and penalty (job.inp); "
            "differences relative to gearfe (load shares: absolute; cost: ratio CalculiX / gearfe).\n\n")
    (folder / "crosscheck.md").write_text(head + md)
    (folder / "crosscheck.json").write_text(json.dumps({"rows": rows, "gearfe": asdict(g), "calculix": asdict(c)}, indent=2) + "\n")
    print(md, end="")
    print(f"results in {folder}/crosscheck.md, crosscheck.json (ccx files in {folder}/ccx/)")
    return 0
