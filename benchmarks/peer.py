"""Peer benchmark: the same gear scene solved by gearfe and by CalculiX at three mesh sizes (issue 13).

Run: ``python -m benchmarks.peer --out DIR [--quick]`` (``make bench`` runs it as area
``peer``). Writes ``DIR/peer.md`` and ``DIR/peer.json``.

The scene is ``pipelines/cases/stress_pair_small.toml`` (Table 1.1 sun driving the double-crowned
planet, Δγ = 3′, position of maximum TE, three teeth per gear) with ``[fe] element = "C3D8"``
(CalculiX's C3D8I adds three internal nodes per element, about 3.3 times the equations) at
``mesh.refine`` = 0.5, 0.8 and 1.2 (the last ≥ 100k DOF). Each level: ``gearfe stress --inp``
(TCA, mesh, contact solve), then ``gearfe crosscheck`` (ccx on job.inp: SPOOLES, one thread).
Per level the side-by-side rows of :mod:`pipelines.calculix.crosscheck` (contact force, reaction
torque, load shares, maximum von Mises per body, fillet maximum principal stress, peak contact
pressure, maximum displacement, wall time and peak memory) and the speed ratio
t_CalculiX / t_gearfe of the solves. Without ccx the benchmark writes that and exits 0.

Measured with ``--quick`` (refine 0.3 / 0.4 / 0.5, 25.7k / 36.4k / 50.5k DOF, load 8.6 on 2 cores):
gearfe 6.2 / 8.8 / 6.1 s, CalculiX 73 / 178 / 426 s (ratio 12 / 20 / 70); contact force and reaction
torque within 0.11 %, fillet maximum principal stress within 1.3 %; maximum von Mises 5-14 % lower
and nodal peak pressure 2-6 times higher in CalculiX (docs/deviations.md). The full levels were not
run before the branch was handed over (CalculiX at ~160k DOF: expect an hour or more).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import time
from pathlib import Path

from pipelines.cases.reader import load_case
from pipelines.cases.schema import Table
from pipelines.cases.stress import read_stress_case
from pipelines.calculix.job import CCX_INSTALL
from pipelines.calculix.crosscheck import crosscheck, table, write_inp_job
from pipelines.models.stress.run import run_stress

__all__ = ["main", "LEVELS", "QUICK"]

CASE = "pipelines/cases/stress_pair_small.toml"
LEVELS = (0.5, 0.8, 1.2)
QUICK = (0.3, 0.4, 0.5)


def level(refine: float, out: Path) -> dict:
    """gearfe and CalculiX on the scene at one refinement: the crosscheck rows and the speed ratio."""
    data = dict(load_case(CASE).data)
    data["mesh"] = {**data.get("mesh", {}), "refine": refine}
    data["fe"] = {**data.get("fe", {}), "element": "C3D8"}
    case = read_stress_case(Table(data, ""))
    out.mkdir(parents=True, exist_ok=True)
    run = run_stress(case, out)
    s = run.summary
    write_inp_job(out, run.scene, run.mesh, run.result, s["solve_s"])
    g, c = crosscheck(out, timeout=4 * 3600.0)  # SPOOLES refactorizes each Newton iteration: long at 150k DOF
    md, rows = table(g, c)
    (out / "crosscheck.md").write_text(md)
    return {"refine": refine, "dofs": s["dofs"], "elements": s["elements"], "gearfe_solve_s": g.wall_s,
            "ccx_s": c.wall_s, "speed_ratio": c.wall_s / g.wall_s, "gearfe_peak_mb": g.peak_memory_mb,
            "ccx_peak_mb": c.peak_memory_mb, "rows": rows, "table": md}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="bench_peer", description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, help="output folder")
    ap.add_argument("--quick", action="store_true", help="three coarse levels (refine 0.3-0.5)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    lines = ["# Peer benchmark: gearfe vs CalculiX on the same scene", "",
             f"Scene: `{CASE}` with C3D8 elements; CalculiX 2.20 (SPOOLES, one thread) on job.inp written by "
             "`gearfe stress --inp` (docs/calculix.md). Load at start {:.2f} on {} cores.".format(os.getloadavg()[0], os.cpu_count()), ""]
    if shutil.which("ccx") is None:
        lines.append(f"CalculiX (ccx) is not installed ({CCX_INSTALL}): nothing measured.")
        (out / "peer.md").write_text("\n".join(lines) + "\n")
        return 0
    t0 = time.perf_counter()
    levels = []
    for r in (QUICK if args.quick else LEVELS):
        x = level(r, out / f"refine_{r:g}")
        levels.append(x)
        print(f"bench_peer: refine {r:g}: {x['dofs']} DOF, gearfe {x['gearfe_solve_s']:.1f} s, ccx {x['ccx_s']:.1f} s "
              f"(x{x['speed_ratio']:.1f})", flush=True)
    lines += ["| refine | DOF | gearfe solve [s] | CalculiX [s] | speed ratio ccx/gearfe | gearfe peak [MB] | CalculiX peak [MB] |",
              "|---|---|---|---|---|---|---|"]
    for x in levels:
        lines.append(f"| {x['refine']:g} | {x['dofs']} | {x['gearfe_solve_s']:.1f} | {x['ccx_s']:.1f} | {x['speed_ratio']:.1f} | "
                     f"{x['gearfe_peak_mb']:.0f} | {x['ccx_peak_mb']:.0f} |")
    for x in levels:
        lines += ["", f"## refine {x['refine']:g} ({x['dofs']} DOF)", "", x["table"]]
    lines += ["", f"Total {time.perf_counter() - t0:.0f} s. gearfe's time is its contact solve (setup, factorization, "
              "active set); CalculiX's the whole ccx run (two steps). gearfe's peak memory is its process's "
              "(TCA and meshing included)."]
    (out / "peer.md").write_text("\n".join(lines) + "\n")
    (out / "peer.json").write_text(json.dumps({"levels": levels}, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
