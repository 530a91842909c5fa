"""ISO 6336 method B rating of a case's gears from its ``[rating]`` table, in seconds (no FE).

``gearfe rate CASE.toml --out DIR`` reads a pair, planetary or stress case with a ``[rating]`` table (speed, life,
lubricant, K_A, material and quality per gear: docs/cases.md), takes the geometry of its gears as every other
command does (Y_F, Y_S of the generated teeth), and writes ``DIR/summary.json`` (key ``rating``: per gear σ_H0,
σ_H, σ_F0, σ_F, the safeties S_H, S_F and every factor with its source and note; docs/rating.md) and
``DIR/rating.md``. The load factors are ISO's (K_Hβ by method C from the case's misalignment); ``gearfe ltca``
rates the pair again with the factors of its loaded TCA. A case outside ISO's assumptions (ε_α < 1, β > 30°) is
rated with a warning; bad input: one line, exit status 2, no files.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from pipelines.analyses.rating import print_rating, rating_record
from pipelines.cases.kinds import read_case
from pipelines.cli.outdir import staged_output
from pipelines.jsonio import plain
from pipelines.report.rating import rating_markdown

__all__ = ["add_args", "handle"]


def add_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("case", help="pair, planetary or stress case with a [rating] table, e.g. "
                   "pipelines/cases/stress_spur_pair.toml")
    p.add_argument("--out", required=True, help="output folder")


def handle(args) -> int:
    t0 = time.perf_counter()
    kind, job = read_case(args.case, "rate")  # bad input fails here, before any output
    rec = plain(rating_record(list(job.meshes)))
    summary = {"kind": "rate", "case": str(args.case), "case_kind": kind.name, "title": job.title, "rating": rec,
               "files": ["summary.json", "rating.md"], "elapsed_s": time.perf_counter() - t0}
    with staged_output(args.out) as tmp:
        (Path(tmp) / "rating.md").write_text(rating_markdown(rec, job.title))
        (Path(tmp) / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    print_rating(rec)
    print(f"results in {args.out}/ (summary.json, rating.md) in {time.perf_counter() - t0:.2f} s")
    return 0
