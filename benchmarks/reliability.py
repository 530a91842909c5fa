"""Reliability (issue 15): run-out TE against the closed form, the resource estimate against real meshes, long isostatic runs.

Run: ``python -m benchmarks.reliability --out DIR``; writes ``DIR/reliability.md``.

* Run-out: an eccentric gear (e = 10, 20, 50 um, phases 0, 90, 217 deg, either gear) of the
  involute Table 1.1 sun/planet pair at the full TCA resolution (40 steps per cycle) over one
  revolution of the eccentric gear; the TE's once-per-revolution amplitude (least-squares sine in
  the eccentric gear's angle) against e / r_b2 (Eq. 3.6, first order), and what the one-harmonic
  fit leaves.
* Resource estimate (``pipelines.models.stress.model.estimate_resources``) against the mesher's element
  and node counts of ``stress_pair_small`` at refine 0.5-2.5.
* Isostatic train of Table 3.1 over 50-200 carrier revolutions (scale-aware Newton targets).
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import time
from pathlib import Path

import numpy as np

from tca.isostatic.analysis import phi1_grid, run_isostatic_tca, scaled_tolerances, IsostaticOptions
from tca.pair.gear_pair import GearPair
from tca.pair.analysis import TCAOptions, run_pair_tca
from tca.report_data import table_1_1_planet, table_1_1_sun
from tca.units import ARCSEC

from pipelines.cases.isostatic import read_train
from pipelines.cases.reader import CASES_DIR, load_case
from pipelines.cases.stress import read_stress_case
from pipelines.models.stress.model import estimate_resources, mesh_scene
from pipelines.models.stress.run import build_scene

__all__ = ["main"]


def runout(lines):
    lines += ["## Run-out: once-per-revolution TE against e / r_b2", "",
              "| eccentric gear | e [um] | phase [deg] | positions | amplitude [arcsec] | e/r_b2 [arcsec] | ratio | "
              "residual rms / amplitude | time [s] |", "|---|---|---|---|---|---|---|---|---|"]
    worst = 0.0
    for which in ("sun", "planet"):
        for e_um in (10.0, 20.0, 50.0):
            for ph in (0.0, 90.0, 217.0):
                sun, planet = table_1_1_sun(10.0), table_1_1_planet(crowned=False)
                kw = dict(runout=e_um * 1e-3, runout_phase=math.radians(ph))
                if which == "sun":
                    sun = dataclasses.replace(sun, **kw)
                else:
                    planet = dataclasses.replace(planet, **kw)
                ecc = sun if which == "sun" else planet
                t0 = time.perf_counter()
                r = run_pair_tca(GearPair(sun, planet), TCAOptions(cycles=ecc.teeth, steps_per_cycle=40))
                dt = time.perf_counter() - t0
                ang = r.phi1 if which == "sun" else r.phi2
                A = np.stack([np.ones_like(ang), np.cos(ang), np.sin(ang)], 1)
                c, *_ = np.linalg.lstsq(A, r.te, rcond=None)
                amp = math.hypot(c[1], c[2])
                rms = float(np.sqrt(np.mean((A @ c - r.te) ** 2)))
                target = e_um * 1e-3 / planet.r_b
                worst = max(worst, abs(amp / target - 1))
                lines.append(f"| {which} | {e_um:g} | {ph:g} | {len(r.phi1)} | {amp / ARCSEC:.3f} | {target / ARCSEC:.3f} | "
                             f"{amp / target:.5f} | {rms / amp:.2e} | {dt:.1f} |")
    lines += ["", f"Largest deviation of the amplitude from e / r_b2: {100 * worst:.3f} % (target: 2 %).", ""]


def resources(lines):
    lines += ["## Resource estimate against real meshes (stress_pair_small)", "",
              "| refine | estimated elements | elements | ratio | estimated DOF | DOF | estimated memory [GB] |",
              "|---|---|---|---|---|---|---|"]
    for refine in (0.5, 1.0, 1.5, 2.0, 2.5):
        t = load_case(CASES_DIR / "stress_pair_small.toml")
        t.data["mesh"] = {**t.data.get("mesh", {}), "refine": refine}
        scene, _ = build_scene(read_stress_case(t))
        est = estimate_resources(scene)
        mesh = mesh_scene(scene)
        lines.append(f"| {refine:g} | {est.elements} | {mesh.n_cells} | {est.elements / mesh.n_cells:.3f} | {est.dofs} | "
                     f"{3 * mesh.n_points} | {est.memory_gb:.3g} |")
    lines.append("")


def isostatic(lines):
    lines += ["## Isostatic train of Table 3.1 over many carrier revolutions", "",
              "| carrier revolutions | positions | Newton target [mm] | max residual [mm] | carrier TE p-p [arcsec] | time [s] |",
              "|---|---|---|---|---|---|"]
    train = read_train(load_case(CASES_DIR / "part3_ideal.toml"))
    for rev in (1, 50, 100, 200):
        phi1 = phi1_grid(train, 200, carrier_revolutions=rev)
        t0 = time.perf_counter()
        r = run_isostatic_tca(train, phi1)
        tol = scaled_tolerances(train, phi1, IsostaticOptions()).tol
        lines.append(f"| {rev} | {len(phi1)} | {tol:.2e} | {float(np.max(r.residual)):.2e} | "
                     f"{float(np.ptp(r.te)) / ARCSEC:.2e} | {time.perf_counter() - t0:.1f} |")
    lines.append("")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", default="out/bench/reliability")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    lines = ["# Reliability benchmarks (issue 15)", ""]
    for part in (runout, resources, isostatic):
        part(lines)
    (out / "reliability.md").write_text("\n".join(lines) + "\n")
    print(f"wrote {out / 'reliability.md'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
