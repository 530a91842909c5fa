"""One load case in one command: TCA, position, mesh, contact FE, images and report.

``gearfe run CASE.toml --out DIR`` runs a stress case (``kind = "stress"``, see
:mod:`pipelines.models.stress.run` for its keys) through every stage and writes into DIR: ``summary.json``
(every key number of ``gearfe stress`` and ``stages``: the wall time of each stage [s]),
``report.html`` (self-contained: tables, the case file and every image embedded),
``report.md``, ``result.vtu``, TCA plots (``tca_te.png``, for a pair ``tca_paths.png``) and
off-screen PNG images (per mesh ``teeth_``, ``flank_``, ``section_``, ``root_``, ``deformed_`` and
``zone_<interface>_<member>.png``, and ``overview.png``; see docs/pictures.md). The position is the case's (by default
the maximum of the transmission error); ``--phi1-deg`` or ``--position`` override it, ``--refine``
overrides ``[mesh] refine``. Progress lines ([stage/6]) go to stderr. On bad input or a failed
solve: one error line, exit status 2, no files.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
import time
from pathlib import Path

from tca.errors import InputError
from tca.pair.te import POSITIONS

from pipelines.cases.stress import torque_record
from pipelines.cli.interrupt import check_interrupted
from pipelines.cases.reader import load_case
from pipelines.cli.outdir import staged_output
from pipelines.report.html import run_html
from pipelines.report.run import run_pipeline
from pipelines.analyses.rating import print_rating
from pipelines.cases.schema import Table
from pipelines.cases.kinds import kind_of, read_checked
from pipelines.models.stress.case import StressCase
from pipelines.calculix.crosscheck import write_inp_job

__all__ = ["add_args", "handle", "read_with_overrides", "SHOWN"]

SHOWN = ("max_von_mises_mpa", "contact_peak_mpa", "max_contact_pressure_mpa", "contact_force_n", "max_fillet_stress_mpa",
         "torque_balance_error", "edge_contact", "fe_edge_contact", "dofs", "total_s")


def add_overrides(p: argparse.ArgumentParser) -> None:
    """Options that override case keys (shared with ``gearfe compare``)."""
    g = p.add_mutually_exclusive_group()
    g.add_argument("--phi1-deg", type=float, default=None, help="analyse at this driving-gear angle [deg]")
    g.add_argument("--position", default=None, help="'max_te' (default), 'min_te', an index of the TCA grid; pair model also "
                   "'pitch', 'hpstc', 'lpstc'")
    p.add_argument("--refine", type=float, default=None, help="element sizes divided by this factor ([mesh] refine)")


def add_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("case", help="stress case file (TOML), e.g. pipelines/cases/stress_part1_new.toml")
    p.add_argument("--out", required=True, help="output folder")
    p.add_argument("--inp", action="store_true",
                   help="also write DIR/job.inp, the CalculiX/ABAQUS job of the same scene (docs/calculix.md)")
    add_overrides(p)
    p.add_argument("--edges", action="store_true", help="draw the element edges on the teeth views")


def read_with_overrides(path, args) -> StressCase:
    """The case file with the command-line overrides applied, validated like the file itself."""
    t = load_case(path)
    data = dict(t.data)
    if args.phi1_deg is not None:
        data.pop("position", None)
        data.pop("roll_deg", None)
        data["phi1_deg"] = args.phi1_deg
    if args.position is not None:
        data.pop("phi1_deg", None)
        data.pop("roll_deg", None)
        # an integer index (ASCII digits only: '²'.isdigit() is true) or a named position
        if re.fullmatch(r"-?[0-9]{1,9}", args.position):
            data["position"] = int(args.position)
        elif args.position in POSITIONS:
            data["position"] = args.position
        else:
            raise InputError("--position", args.position,
                             ", ".join(repr(p) for p in POSITIONS) + " or an integer index of the TCA grid")
    if args.refine is not None:
        if not isinstance(data.get("mesh", {}), dict):
            raise InputError("mesh", data["mesh"], "a table [mesh] (--refine sets mesh.refine)")
        data["mesh"] = {**data.get("mesh", {}), "refine": args.refine}
    t = Table(data, "")
    return read_checked(t, kind_of(t, args.command), args.command)


def progress(msg: str) -> None:
    """Progress line on stderr (and the place where a swallowed Ctrl-C stops the run)."""
    check_interrupted()
    print(f"gearfe: {msg}", file=sys.stderr, flush=True)


def write_summary(summary: dict, path: Path) -> None:
    path.write_text(json.dumps(summary, indent=2) + "\n")


def handle(args) -> int:
    t0 = time.perf_counter()
    case = read_with_overrides(args.case, args)  # bad input fails here, before any output
    with staged_output(args.out) as tmp:
        run = run_pipeline(case, Path(tmp), progress=progress, show_edges=args.edges)
        s = run.summary
        if getattr(args, "inp", False):
            write_inp_job(Path(tmp), run.scene, run.mesh, run.result, s["solve_s"])
            s = {**s, "files": [*s["files"], "job.inp", "crosscheck_ref.npz", "crosscheck_gearfe.json"]}
        s = {"kind": "run", "case": str(args.case), **s, **torque_record(case), "elapsed_s": time.perf_counter() - t0}
        s["files"] = [*s["files"], "report.html"]
        write_summary(s, Path(tmp) / "summary.json")
        run_html(s, Path(tmp), Path(args.case).read_text())
    width = max(len(k) for k in SHOWN)
    geo = s.get("pair_geometry")
    if geo:  # the centre distance analysed and where it comes from (zero backlash of the profile shifts, given)
        print(f"  {'center_distance_mm':<{width}}  {geo['center_distance_mm']:.6g} ({geo['center_distance_source']})")
    for k in SHOWN:
        v = s.get(k)
        print(f"  {k:<{width}}  {v:.6g}" if isinstance(v, float) else f"  {k:<{width}}  {v}")
    for name, share in s["load_share"].items():
        print(f"  load share {name}: " + ", ".join(f"{m} {v:.3f}" for m, v in share["members"].items()))
    print_rating(s.get("rating"))
    print("  stage times [s]: " + ", ".join(f"{k} {v:.1f}" for k, v in s["stages"].items()))
    print(f"results in {args.out}/ (report.html, report.md, summary.json, result.vtu, images: {', '.join(s['images'][:2])}, ...)")
    return 0
