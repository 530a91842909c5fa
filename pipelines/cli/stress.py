"""Contact stress analysis of a gear pair or Part 1's twin subgear drive at a TCA position (section 1.6).

``gearfe stress CASE.toml --out DIR`` runs the TCA (and the axial regulation of Part 1), meshes the
three-tooth models, solves the penalty contact problem (C3D8I-like elements, Fig. 1.7 boundary
conditions) and writes ``DIR/result.vtu`` (displacements, stresses, von Mises, principal stresses,
contact pressure and gap, reactions) and ``DIR/summary.json`` (``max_von_mises_mpa``,
``max_contact_pressure_mpa``, ``contact_force_n``, ``max_fillet_stress_mpa``, ``torque_balance_error``,
``dofs``, ``solve_s``, ``load_share`` per interface, member and tooth, edge contact, ...); with ``--inp``
also ``DIR/job.inp``, the complete CalculiX job of the same scene (``docs/calculix.md``), for
``gearfe crosscheck DIR``. Progress
lines go to stderr. Nothing is written when the case is invalid or a solve fails (exit status 2).
See :mod:`pipelines.models.stress.run` (docs/cases.md) for the case keys and ``pipelines/cases/stress_*.toml`` for examples.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from pipelines.cases.stress import torque_record
from pipelines.cli.interrupt import check_interrupted
from pipelines.cli.outdir import staged_output
from pipelines.cases.kinds import read_case
from pipelines.calculix.crosscheck import write_inp_job
from pipelines.models.stress.run import run_stress

__all__ = ["add_args", "handle", "SHOWN"]

SHOWN = ("max_von_mises_mpa", "max_contact_pressure_mpa", "contact_force_n", "max_fillet_stress_mpa",
         "torque_balance_error", "torque_balance_error_kinematic", "edge_contact", "fe_edge_contact", "dofs",
         "tca_s", "mesh_s", "solve_s", "total_s")


def add_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("case", help="stress case file (TOML), e.g. pipelines/cases/stress_part1_new.toml")
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--inp", action="store_true",
                   help="also write DIR/job.inp, the CalculiX/ABAQUS job of the same scene (docs/calculix.md), "
                        "and the reference files of 'gearfe crosscheck DIR'")


def _progress(msg: str) -> None:
    check_interrupted()
    print(f"gearfe stress: {msg}", file=sys.stderr, flush=True)


def handle(args) -> int:
    t0 = time.perf_counter()
    _, case = read_case(args.case, "stress")  # bad input fails here, before any output
    with staged_output(args.out) as tmp:
        run = run_stress(case, Path(tmp), progress=_progress)
        summary = run.summary
        files = ["result.vtu", "summary.json"]
        if args.inp:
            write_inp_job(Path(tmp), run.scene, run.mesh, run.result, summary["solve_s"])
            files += ["job.inp", "crosscheck_ref.npz", "crosscheck_gearfe.json"]
        summary = {"kind": "stress", "case": str(args.case), **summary, **torque_record(case), "files": files,
                   "elapsed_s": time.perf_counter() - t0}
        (Path(tmp) / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    width = max(len(k) for k in SHOWN)
    geo = summary.get("pair_geometry")
    if geo:  # the centre distance analysed and where it comes from (zero backlash of the profile shifts, given)
        print(f"  {'center_distance_mm':<{width}}  {geo['center_distance_mm']:.6g} ({geo['center_distance_source']})")
    for k in SHOWN:
        v = summary.get(k)
        print(f"  {k:<{width}}  {v:.6g}" if isinstance(v, float) else f"  {k:<{width}}  {v}")
    for name, share in summary["load_share"].items():
        members = ", ".join(f"{m} {v:.3f}" for m, v in share["members"].items())
        print(f"  load share {name}: {members}")
    print(f"results in {args.out}/")
    return 0
