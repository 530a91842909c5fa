"""Tooth contact analysis of a case: a gear pair, a planetary train (Parts 1 and 3), a face-gear train (Part 2).

The case file's ``kind`` selects the analysis (the registry :mod:`pipelines.cases.kinds`);
results go to ``--out DIR``: ``summary.json`` (key numbers), ``tca.csv`` (per position) and PNG plots.
Nothing is written when the case is invalid or a solve fails.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path


from pipelines.cases.reader import load_case
from pipelines.cases.kinds import analysis_module, kind_of, validate_case
from pipelines.cli.outdir import staged_output
from pipelines.jsonio import to_json

__all__ = ["add_args", "handle", "run_case"]

def add_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("case", help="case file (TOML), e.g. pipelines/cases/part1_sun_planet.toml")
    p.add_argument("--out", required=True, help="output folder")


def run_case(case, out: Path, label: str = "") -> dict:
    """Run a TCA case (a strict Table) writing its files into `out`; returns the summary (also written)."""
    kind = kind_of(case, "tca")
    case.get("kind", str)
    case.get("title", str, "")
    t0 = time.perf_counter()
    summary = analysis_module(kind).run(case, Path(out))
    case.done()
    summary = {"kind": kind.name, "case": label, **summary, "elapsed_s": time.perf_counter() - t0}
    (Path(out) / "summary.json").write_text(json.dumps(summary, indent=2, default=to_json) + "\n")
    return summary


def handle(args) -> int:
    case = load_case(args.case)
    validate_case(case, "tca")  # every key, range and geometry check before any work
    with staged_output(args.out) as tmp:
        summary = run_case(case, Path(tmp), str(args.case))
    _print_summary(summary, args.out)
    return 0


def _print_summary(summary: dict, out) -> None:
    keys = [k for k, v in summary.items() if isinstance(v, (int, float, bool, str)) and k not in ("case",)]
    width = max(len(k) for k in keys)
    for k in keys:
        v = summary[k]
        print(f"  {k:<{width}}  {v:.6g}" if isinstance(v, float) else f"  {k:<{width}}  {v}")
    print(f"results in {out}/")
