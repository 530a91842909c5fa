"""Loaded TCA of a gear pair over a mesh cycle from condensed flank compliances.

``gearfe ltca CASE.toml --out DIR`` reads a stress case (``kind = "stress"``, ``model = "pair"``) with an
optional ``[ltca]`` table (positions, torques, flank grid; :mod:`pipelines.cases.ltca`), builds each
gear's flank compliance once from its hexahedral model, then solves the contact of every pair of
teeth within reach at every position and torque. Writes ``results.csv``, ``pressure.csv``,
``te_loaded.png``, ``load_share.png``, ``pressure.png``, ``mesh_stiffness.png`` and ``summary.json``
(with ``check_positions`` > 0 also the check against the full contact FE). Progress on stderr.
Nothing is written when the case is invalid, the resource plan exceeds ``GEARFE_MAX_MEMORY_GB`` or a solve
fails (exit status 2). When the check against the full contact FE misses one of its targets, the results are
written and the last line names the missed target (exit status 3).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from pipelines.cases.stress import torque_record
from pipelines.cli import EXIT_CHECK
from pipelines.cli.interrupt import check_interrupted
from pipelines.cli.outdir import staged_output
from pipelines.cases.kinds import read_case
from pipelines.models.ltca.run import progress_bar, run_ltca
from pipelines.analyses.rating import ltca_rating, print_rating, train_rating
from pipelines.jsonio import plain

__all__ = ["add_args", "handle"]


def add_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("case", help="stress case file (TOML, model = 'pair'), e.g. pipelines/cases/ltca_pair_small.toml, "
                   "or a train case (kind 'isostatic' or 'planetary'), e.g. pipelines/cases/part3_indexing.toml")
    p.add_argument("--out", required=True, help="output folder")


def _say(msg: str) -> None:
    check_interrupted()
    print(f"gearfe ltca: {msg}", file=sys.stderr, flush=True)


def handle(args) -> int:
    t0 = time.perf_counter()
    kind, read = read_case(args.case, "ltca")  # bad input fails here, before any output
    if kind.name in ("isostatic", "planetary"):
        return _handle_train(args, read, t0)
    case, opts = read
    bar = progress_bar("gearfe ltca: positions")
    with staged_output(args.out) as tmp:
        try:
            s = run_ltca(case, opts, Path(tmp), say=_say, bar=bar)
        finally:
            bar.close()  # an error raised mid-run starts on a line of its own
        s = {**s, **torque_record(case), "case": str(args.case), "rating": plain(ltca_rating(case, s, tmp)), "elapsed_s": time.perf_counter() - t0}
        s["files"] = s["files"] + ["summary.json"]
        (Path(tmp) / "summary.json").write_text(json.dumps(s, indent=2) + "\n")
    t = s["timing"]
    print(f"  build_s                    {s['build_s']:.3g}")
    print(f"  solve_all_s                {s['solve_all_s']:.3g}  ({t['positions']} positions x {t['torques']} torques)")
    print(f"  per_position_s             {t['per_position_s']:.3g}")
    print(f"  per_torque_per_position_s  {t['per_torque_per_position_s']:.3g}")
    for T, v in s["te_loaded_peak_to_peak_arcsec"].items():
        print(f"  loaded TE peak-to-peak at {T} N m: {v:.3g} arcsec")
    if s["fe_check"]:
        w, m = s["fe_check"]["worst"], s["fe_check"]["met"]
        for k, v in w.items():
            print(f"  check vs full FE, {k}: worst {v:.4g} (target {s['fe_check']['targets'][k]}: {'met' if m[k] else 'MISSED'})")
    print_rating(s["rating"])
    print(f"results in {args.out}/")
    missed = [k for k, ok in (s["fe_check"] or {}).get("met", {}).items() if not ok]
    if missed:
        w, tg = s["fe_check"]["worst"], s["fe_check"]["targets"]
        print("gearfe ltca: check failed: " + "; ".join(f"{k} worst {w[k]:.4g} > target {tg[k]}" for k in missed)
              + f" against the full contact FE (results written to {args.out}/)", file=sys.stderr)
        return EXIT_CHECK
    return 0


def _handle_train(args, case, t0: float) -> int:
    """A planetary train (docs/trains.md): shares, K_gamma, loaded TE, sun centre path."""
    from pipelines.models.trains.ltca import run_train_ltca

    bar = progress_bar("gearfe ltca: positions")
    with staged_output(args.out) as tmp:
        try:
            s = run_train_ltca(case, Path(tmp), say=_say, bar=bar)
        finally:
            bar.close()  # an error raised mid-run starts on a line of its own
        s = {**s, "case": str(args.case), "rating": plain(train_rating(case, s)), "elapsed_s": time.perf_counter() - t0}
        s["files"] = s["files"] + ["summary.json"]
        (Path(tmp) / "summary.json").write_text(json.dumps(plain(s), indent=2) + "\n")
    t = s["timing"]
    print(f"  build_s                    {s['build_s']:.3g}")
    print(f"  solve_all_s                {s['solve_all_s']:.3g}  ({t['positions']} positions x {t['torques']} torques)")
    print(f"  per_position_s             {t['per_position_s']:.3g}")
    print(f"  per_torque_per_position_s  {t['per_torque_per_position_s']:.3g}")
    for p in s["torques"]:
        line = f"  T = {p['torque_nm']:g} N m on the sun: K_gamma {p['k_gamma']:.4f}"
        if "k_gamma_members" in p:
            line += f", K_gamma of the members {p['k_gamma_members']:.4f}"
        print(line)
        for u in p["unloaded_planets"]:
            print(f"    planet {u['planet']} carries no load at {u['positions']} position(s)")
    print_rating(s["rating"])
    print(f"results in {args.out}/")
    return 0
