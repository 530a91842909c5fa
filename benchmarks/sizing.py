"""Models sized by the loaded TCA (issue 26): speed against error of the new defaults beside the models before it.

Run: ``python -m benchmarks.sizing --out DIR`` (``make bench`` area ``sizing``; about 15 min on a quiet 2-core
machine, needs ~10 GB for the twin drive sized as before); ``--quick`` runs the estimate sweep alone (no solve).

Rows, each solved in its own process (its peak resident memory is the row's memory):

* the shipped crowned pair (``stress_pair_small.toml`` at the default refine 1, position of maximum TE):
  ``sizing = "loaded"`` (the new default) at refine 0.71, 1 and 1.41 (Richardson's value of the fillet stress and
  of the peak pressure from the three), and ``sizing = "tca"`` at refine 1 (the model before issue 26);
* the FZG-type aligned spur pair (16/24, m 4.5, b 14, x 0.18/0.17, a = 91.5 mm, 120 N m) at the pitch point,
  against Hertz's line contact of the whole load;
* Part 1's twin drive, new design (``stress_part1_new.toml``): its shipped refine with both sizings.

``--fourth`` runs the fourth round's study of the fillet target instead (:data:`FOURTH`, docs/benchmarks.md "Fourth
round: the fillet target"): the crowned pair at refine 1, one region varied at a time from the third round's default.

``--line`` runs the fifth round's study of the axial size of a line contact instead (:data:`LINE`, (G7) of
:mod:`pipelines.models.stress.sizing`): the FZG pair aligned and misaligned by 2', the shipped spur and internal pairs,
their axial sizes a/12 (reference), a/6, a/4 and a/3. About 2 min on a quiet 2-core machine.

``--grading`` runs the grading study of issue 26, item 2 instead (:data:`GRADING`, docs/benchmarks.md "Third round:
grading away from the zones"): the crowned pair at refine 1 with the fillet arc size, the axial spacing outside the
zones, the growth across the tooth and the coarse size varied one at a time, and two reference sequences (the fillet
size halved at refine 1; refine 0.71/1/1.41 with the fillet 0.1 mm / refine), each with Richardson's value of its
fillet stress. About 10 min on a quiet 2-core machine; its finest row (485k DOF) needs ~7 GB.

Then the resource estimate against the mesh (no solve) for every shipped stress case and the aligned and
misaligned (Δγ = 3′) helical pair at refine 0.25, 0.5 and 1: within −10 %/+20 % of the mesh built, or refused
before meshing when it exceeds the memory limit (``GEARFE_MAX_MEMORY_GB``).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from tca.errors import InputError

from benchmarks.convergence import richardson
from pipelines.cases.kinds import kind_of, read_checked
from pipelines.cases.reader import CASES_DIR, load_case
from pipelines.cases.schema import Table
from pipelines.models.stress.model import check_resources, estimate_resources, mesh_scene
from pipelines.models.stress.run import build_scene, run_stress

__all__ = ["main", "ROWS", "FZG", "GRADING", "FOURTH", "LINE", "run_row", "estimate_sweep", "grading_study",
           "line_study"]

FZG = {"gears.pinion.teeth": 16, "gears.pinion.profile_shift": 0.18, "gears.wheel.profile_shift": 0.17,
       "center_distance_mm": 91.5}
R2 = 2 ** 0.5
ROWS = [
    ("crowned pair, loaded, refine 0.71", "stress_pair_small", {"mesh.refine": 1 / R2}),
    ("crowned pair, loaded, refine 1 (default)", "stress_pair_small", {"mesh.refine": 1.0}),
    ("crowned pair, loaded, refine 1.41", "stress_pair_small", {"mesh.refine": R2}),
    ("crowned pair, tca, refine 1 (before)", "stress_pair_small", {"mesh.refine": 1.0, "mesh.sizing": "tca"}),
    ("FZG spur pair, loaded (default)", "stress_spur_pair", FZG),
    ("FZG spur pair, tca (before)", "stress_spur_pair", {**FZG, "mesh.sizing": "tca"}),
    ("twin new design, loaded (default)", "stress_part1_new", {}),
    ("twin new design, tca (before)", "stress_part1_new", {"mesh.sizing": "tca"}),
]
# the grading study (item 2): label, case overrides, SizeRules overrides (pipelines.models.stress.sizing (G1)-(G3) of
# the third round, pinned here so that the rows stay those of docs/benchmarks.md: growth 1.3, the layers across the
# tooth at one growth); "before" is the grading of main before the third round except the split surface (graded since)
_BEFORE = {"axial_coarse": 1.5, "section_growth": 1.3, "depth_growth": 1.3}  # axial to the coarse size, growth 1.3
_G13 = {"mesh.growth": 1.3}
_L15 = {"section_growth": 1.5, "depth_growth": 1.5}  # the third round's (G3)
GRADING = [
    ("fillet 0.2 mm, before (159,840 DOF on main)", {**_G13, "mesh.fillet_size_mm": 0.2}, _BEFORE),
    ("fillet 0.1 mm", {**_G13, "mesh.fillet_size_mm": 0.1}, _BEFORE),
    ("fillet 0.05 mm", {**_G13, "mesh.fillet_size_mm": 0.05}, _BEFORE),
    ("fillet 0.1 mm, axial coarse 3 mm (G2)", {**_G13, "mesh.fillet_size_mm": 0.1},
     {"section_growth": 1.3, "depth_growth": 1.3}),
    ("fillet 0.1 mm, coarse 2 mm", {**_G13, "mesh.fillet_size_mm": 0.1, "mesh.coarse_size_mm": 2.0},
     {"axial_coarse": 2.0, "section_growth": 1.3, "depth_growth": 1.3}),
    ("fillet 0.2 mm, growth 1.5 everywhere", {"mesh.fillet_size_mm": 0.2, "mesh.growth": 1.5},
     {"axial_coarse": 1.5, **_L15}),
    ("third round's default: fillet 0.1 mm (G1), axial coarse 3 mm (G2), section growth 1.5 (G3)",
     {**_G13, "mesh.fillet_size_mm": 0.1}, _L15),
    ("reference: refine 0.71, fillet 0.1 mm / refine", {**_G13, "mesh.refine": 1 / R2, "mesh.fillet_size_mm": 0.1},
     _BEFORE),
    ("reference: refine 1.41, fillet 0.1 mm / refine", {**_G13, "mesh.refine": R2, "mesh.fillet_size_mm": 0.1},
     _BEFORE),
]
# the fourth round (the fillet target, docs/benchmarks.md "Fourth round: the fillet target"): the crowned pair at
# refine 1, one region varied at a time from the third round's default, then the new default (G1)-(G6)
_THIRD = ({**_G13, "mesh.fillet_size_mm": 0.1}, _L15)
FOURTH = [
    ("third-round default (fillet 0.1 mm, growth 1.3, layers 1.5)", *_THIRD),
    ("fillet arc and back layer 0.08 mm", {**_THIRD[0], "mesh.fillet_size_mm": 0.08}, _THIRD[1]),
    ("coarse 2 mm", {**_THIRD[0], "mesh.coarse_size_mm": 2.0}, _THIRD[1]),
    ("other teeth's flanks 0.4 mm", {**_THIRD[0], "mesh.neighbour_size_mm": 0.4}, _THIRD[1]),
    ("axial growth 1.5", _THIRD[0], {**_THIRD[1], "axial_growth": 1.5}),
    ("back layer 0.3 mm", _THIRD[0], {**_THIRD[1], "back": 0.3}),
    ("back layer 0.05 mm", _THIRD[0], {**_THIRD[1], "back": 0.05}),
    ("layers 1.3 both sides", _THIRD[0], {"section_growth": 1.3, "depth_growth": 1.3}),
    ("layers 1.4 both sides, axial growth 1.5", _THIRD[0], {"section_growth": 1.4, "depth_growth": 1.4,
                                                           "axial_growth": 1.5}),
    ("fillet layers 1.35, depth 1.5, axial growth 1.5", _THIRD[0], {"section_growth": 1.35, "depth_growth": 1.5,
                                                                   "axial_growth": 1.5}),
    ("fillet 0.09 mm, fillet layers 1.35, depth 1.5, axial growth 1.5", {**_THIRD[0], "mesh.fillet_size_mm": 0.09},
     {"section_growth": 1.35, "depth_growth": 1.5, "axial_growth": 1.5}),
    ("new default: fillet 0.09 mm (G1), growth 1.5 (G4), fillet layers 1.3 (G3), depth 1.5 (G5)", {}, {}),
]
# the fifth round (docs/benchmarks.md "Fifth round: the axial size of a uniform line contact", (G7)): spur line
# contacts with the axial size at fractions of the loaded line's half-length a = 7 mm (half the face), against a/12
_A = 7.0
_MIS = {**FZG, "misalignment.d_gamma_arcmin": 2.0}
LINE = [
    ("FZG pair, a/12", "stress_spur_pair", FZG, {"axial": _A / 12}),
    ("FZG pair, a/6 (before)", "stress_spur_pair", FZG, {"axial": _A / 6}),
    ("FZG pair, default (a/4: uniform line load)", "stress_spur_pair", FZG, {}),
    ("FZG pair, a/3", "stress_spur_pair", FZG, {"axial": _A / 3}),
    ("FZG pair misaligned 2', a/12", "stress_spur_pair", _MIS, {"axial": _A / 12}),
    ("FZG pair misaligned 2', default (a/6: w_min/w_max 0.34)", "stress_spur_pair", _MIS, {}),
    ("FZG pair misaligned 2', a/4", "stress_spur_pair", _MIS, {"axial": _A / 4}),
    ("shipped spur pair, a/12", "stress_spur_pair", {}, {"axial": _A / 12}),
    ("shipped spur pair, default (a/4)", "stress_spur_pair", {}, {}),
    ("internal pair, a/12", "stress_internal_pair", {}, {"axial": _A / 12}),
    ("internal pair, default (a/4)", "stress_internal_pair", {}, {}),
]
HELICAL = {"aligned": {}, "misaligned": {"misalignment": {"d_gamma_arcmin": 3.0}}}


def _table(name: str, overrides: dict) -> Table:
    """A shipped case with dotted-key overrides."""
    t = load_case(CASES_DIR / f"{name}.toml")
    for key, value in overrides.items():
        *path, last = key.split(".")
        d = t.data
        for p in path:
            d = d.setdefault(p, {})
        d[last] = value
    return t


def _case(name: str, overrides: dict):
    """A shipped case read as ``gearfe stress`` reads it (its kind's reader: a pair, twin or train stress case)."""
    t = _table(name, overrides)
    return read_checked(t, kind_of(t, "stress"), "stress")


def run_row(name: str, overrides: dict, rules: dict | None = None) -> dict:
    """One solved case: DOF, times [s], peak pressure, fillet and von Mises stresses [MPa], shares, Hertz.

    ``rules``: fields of the case's :class:`pipelines.models.stress.sizing.SizeRules` to replace (those without a
    case key: ``axial_coarse``, ``section_growth``). Also the FE phases' times (``fe_timings_s``: assembly,
    reduction, contact set-up, factor, solve, contact, recovery) and the 1-minute load average before and after (a
    timing on a busy machine says so)."""
    case = _case(name, overrides)
    if rules:
        case = dataclasses.replace(case, mesh=dataclasses.replace(case.mesh, **rules))
    load0 = os.getloadavg()[0]
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as d:
        s = run_stress(case, Path(d)).summary
    shares = {f"{k}/{m}": max([v for t, v in d["teeth"].items() if t.startswith(m + "/")], default=0.0)
              for k, d in s["load_share"].items() for m in d["members"]}
    members = {f"{k}/{m}": d["members"][m] for k, d in s["load_share"].items() for m in d["members"]}
    hz = [m["hertz_estimate"]["p0_mpa"] for d in s["interfaces"].values() for m in d["members"].values()]
    return {"dofs": s["dofs"], "total_s": time.perf_counter() - t0, "tca_s": s["tca_s"], "mesh_s": s["mesh_s"],
            "solve_s": s["solve_s"], "p": s["max_contact_pressure_mpa"], "fillet": s["max_fillet_stress_mpa"],
            "von_mises": s["max_von_mises_mpa"], "max_pair_share": shares, "member_share": members, "hertz_p0": max(hz),
            "warnings": s["warnings"], "peak_gb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6,
            "fe_timings_s": s["fe"]["timings_s"], "load_average": (load0, os.getloadavg()[0])}


def estimate_sweep() -> list[dict]:
    """Estimate against mesh (or refusal) of every shipped stress case and the helical pairs at refine 0.25-1."""
    cases = [(p.stem, {}) for p in sorted(CASES_DIR.glob("stress_*.toml"))]
    cases += [("stress_helical_pair", {"mesh.refine": r, **({"misalignment.d_gamma_arcmin": 3.0} if k else {})})
              for k in (False, True) for r in (0.25, 0.5, 1.0)]
    rows = []
    for name, ov in cases:
        case = _case(name, ov)
        scene, _ = build_scene(case)
        est = estimate_resources(scene)
        row = {"case": name, "overrides": ov, "estimated_dofs": est.dofs, "estimated_gb": est.memory_gb}
        try:
            check_resources(scene, case.mesh)
        except InputError as e:
            rows.append({**row, "refused": str(e)})
            continue
        mesh = mesh_scene(scene)
        rows.append({**row, "dofs": 3 * mesh.n_points, "ratio": est.dofs / (3 * mesh.n_points)})
        print(f"bench_sizing: {name} {ov}: estimated {est.dofs}, meshed {3 * mesh.n_points} DOF", flush=True)
    return rows


def _child(label: str, flag: str = "--row") -> dict:
    """A row solved in a fresh process (its peak memory is the row's)."""
    p = subprocess.run([sys.executable, "-m", "benchmarks.sizing", flag, label], capture_output=True, text=True,
                       check=True)
    return json.loads(p.stdout.strip().splitlines()[-1])


def _write_study(out: Path, name: str, lines: list[str], rows: dict) -> None:
    """A study's table ``out/<name>.md`` and its rows ``out/<name>.json``."""
    out.mkdir(parents=True, exist_ok=True)
    (out / f"{name}.md").write_text("\n".join(lines) + "\n")
    (out / f"{name}.json").write_text(json.dumps(rows, indent=1, default=str))


def fourth_study(out: Path) -> dict:
    """The rows of :data:`FOURTH` (each in its own process), written to ``out/fourth.md``."""
    rows = {label: _child(label, "--fourth-row") for label, _, _ in FOURTH}
    L = ["# Fourth round: the fillet target (crowned pair at refine 1)", "",
         "| variant | DOF | fillet [MPa] | peak pressure [MPa] | solve [s] |", "|---|---|---|---|---|"]
    L += [f"| {k} | {r['dofs']} | {r['fillet']:.1f} | {r['p']:.1f} | {r['solve_s']:.1f} |" for k, r in rows.items()]
    _write_study(out, "fourth", L, rows)
    return rows


def line_study(out: Path) -> dict:
    """The rows of :data:`LINE` (each in its own process), written to ``out/line.md``."""
    rows = {label: _child(label, "--line-row") for label, _, _, _ in LINE}
    L = ["# Fifth round: the axial size of a uniform line contact (G7)", "",
         "| variant | DOF | end to end [s] | peak pressure [MPa] | Hertz p0 [MPa] | fillet [MPa] | max von Mises "
         "[MPa] |",
         "|---|---|---|---|---|---|---|"]
    L += [f"| {k} | {r['dofs']} | {r['total_s']:.1f} | {r['p']:.1f} | {r['hertz_p0']:.1f} | {r['fillet']:.2f} | "
          f"{r['von_mises']:.1f} |" for k, r in rows.items()]
    _write_study(out, "line", L, rows)
    return rows


def grading_study(out: Path) -> dict:
    """The rows of :data:`GRADING` (each in its own process), written to ``out/grading.md`` with the Richardson values
    of the two reference sequences (fillet size 0.2/0.1/0.05 mm at refine 1; refine 0.71/1/1.41)."""
    rows = {}
    for label, _, _ in GRADING:
        rows[label] = _child(label, "--grading-row")
        print(f"bench_sizing: {label}: {rows[label]['dofs']} DOF, fillet {rows[label]['fillet']:.1f} MPa", flush=True)
    L = ["# Grading away from the zones (issue 26, item 2): crowned pair at refine 1", "",
         "| variant | DOF | solve [s] | peak memory [GB] | fillet [MPa] | peak pressure [MPa] | largest pair share |",
         "|---|---|---|---|---|---|---|"]
    for label, r in rows.items():
        sh = ", ".join(f"{v:.3f}" for v in r["max_pair_share"].values())
        L.append(f"| {label} | {r['dofs']} | {r['solve_s']:.1f} | {r['peak_gb']:.2f} | {r['fillet']:.1f} | {r['p']:.1f} "
                 f"| {sh} |")
    lab = [x[0] for x in GRADING]
    seqs = {"fillet size 0.2/0.1/0.05 mm at refine 1": ([0.2, 0.1, 0.05], lab[0:3]),
            "refine 0.71/1/1.41, fillet 0.1 mm / refine": ([R2, 1.0, 1 / R2], [lab[7], lab[1], lab[8]])}
    for name, (h, keys) in seqs.items():
        try:
            x = richardson(h, [rows[k]["fillet"] for k in keys])
            L += ["", f"Richardson ({name}): {x.value:.1f} MPa (order {x.order:.2f}); the new default "
                  f"{rows[lab[6]]['fillet'] / x.value - 1:+.1%}"]
        except InputError as e:
            L += ["", f"Richardson ({name}): none ({e})"]
    _write_study(out, "grading", L, rows)
    return rows


def write_report(rows: dict, sweep: list[dict], out: Path) -> None:
    L = ["# Models sized by the loaded TCA (issue 26)", "",
         "| model | DOF | total [s] | solve [s] | peak memory [GB] | peak pressure [MPa] | fillet [MPa] | largest pair share |",
         "|---|---|---|---|---|---|---|---|"]
    for label, r in rows.items():
        sh = ", ".join(f"{k} {v:.3f}" for k, v in r["max_pair_share"].items())
        L.append(f"| {label} | {r['dofs']} | {r['total_s']:.1f} | {r['solve_s']:.1f} | {r['peak_gb']:.2f} | {r['p']:.1f} | "
                 f"{r['fillet']:.1f} | {sh} |")
    levels = [rows[label] for label, _, ov in ROWS[:3] if label in rows]
    if len(levels) == 3:
        for key in ("fillet", "p"):
            try:  # element sizes h = 1/refine
                x = richardson([R2, 1.0, 1 / R2], [r[key] for r in levels])
                L += ["", f"Richardson ({key}) from refine 0.71/1/1.41: {x.value:.1f} MPa (order {x.order:.2f}); "
                      f"the default (refine 1) {levels[1][key] / x.value - 1:+.1%}"]
            except InputError as e:
                L += ["", f"Richardson ({key}): none ({e})"]
    fzg = rows.get(ROWS[4][0])
    if fzg:
        L += ["", f"FZG pair: peak pressure / Hertz p0 = {fzg['p'] / fzg['hertz_p0']:.4f}"]
    L += ["", "## Resource estimate against the mesh", "", "| case | overrides | estimated DOF | meshed DOF | ratio |",
          "|---|---|---|---|---|"]
    for r in sweep:
        L.append(f"| {r['case']} | {r['overrides']} | {r['estimated_dofs']} | {r.get('dofs', 'refused')} | "
                 f"{r['ratio']:.3f} |" if "ratio" in r else
                 f"| {r['case']} | {r['overrides']} | {r['estimated_dofs']} | refused ({r['estimated_gb']:.1f} GB) | – |")
    (out / "sizing.md").write_text("\n".join(L) + "\n")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="bench_sizing", description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out/bench/sizing")
    ap.add_argument("--quick", action="store_true", help="the estimate sweep alone (no solve)")
    ap.add_argument("--grading", action="store_true", help="the grading study (issue 26 item 2) alone")
    ap.add_argument("--row", help=argparse.SUPPRESS)  # one row in this process (the parent's child)
    ap.add_argument("--grading-row", help=argparse.SUPPRESS)
    ap.add_argument("--fourth", action="store_true", help="the fourth round's study (the fillet target) alone")
    ap.add_argument("--fourth-row", help=argparse.SUPPRESS)
    ap.add_argument("--line", action="store_true", help="the fifth round's study (axial size of line contacts) alone")
    ap.add_argument("--line-row", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.row is not None:
        _, name, ov = next(r for r in ROWS if r[0] == args.row)
        print(json.dumps(run_row(name, ov)))
        return 0
    if args.grading_row is not None:
        _, ov, rules = next(r for r in GRADING if r[0] == args.grading_row)
        print(json.dumps(run_row("stress_pair_small", {"mesh.refine": 1.0, **ov}, rules)))
        return 0
    if args.fourth_row is not None:
        _, ov, rules = next(r for r in FOURTH if r[0] == args.fourth_row)
        print(json.dumps(run_row("stress_pair_small", {"mesh.refine": 1.0, **ov}, rules)))
        return 0
    if args.line_row is not None:
        _, name, ov, rules = next(r for r in LINE if r[0] == args.line_row)
        print(json.dumps(run_row(name, ov, rules or None)))
        return 0
    out = Path(args.out)
    if args.line:
        line_study(out)
        print(f"wrote {out / 'line.md'}")
        return 0
    if args.fourth:
        fourth_study(out)
        print(f"wrote {out / 'fourth.md'}")
        return 0
    if args.grading:
        grading_study(out)
        print(f"wrote {out / 'grading.md'}")
        return 0
    out.mkdir(parents=True, exist_ok=True)
    rows = {}
    if not args.quick:
        for label, _, _ in ROWS:
            rows[label] = _child(label)
            print(f"bench_sizing: {label}: {rows[label]['dofs']} DOF, {rows[label]['total_s']:.1f} s", flush=True)
    sweep = estimate_sweep()
    write_report(rows, sweep, out)
    (out / "sizing.json").write_text(json.dumps({"rows": rows, "sweep": sweep, "max_memory_gb": os.environ.get(
        "GEARFE_MAX_MEMORY_GB")}, indent=1, default=str))
    print(f"wrote {out / 'sizing.md'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
