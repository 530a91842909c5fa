"""`make bench` area ``ltca``: speed and accuracy of the loaded TCA (issue 18) against the full contact FE.

Case: ``pipelines/cases/ltca_pair_small.toml`` (Table 1.1 sun / double-crowned planet, Δγ = 3 arcmin).

1. Speed: the one-off build (TCA and both flank compliances), then 100 positions over one mesh
   cycle at T = 156 N m; the cost of a further position and of a further torque.
2. Accuracy: ``gearfe stress`` of the same case (its own ``[mesh]``, default refine 1) at 6
   positions, both sides of each change of the pair in contact included: elastic rotation,
   load shares, peak contact pressure against the targets of :data:`pipelines.models.ltca.run.TARGETS`.
3. Torque sweep at the position whose next pair of teeth is closest to contact among those
   carried by one pair at the nominal torque: mesh stiffness (normal force over normal approach)
   of the loaded TCA at 8 torques and of the full FE at 3.

Writes ``<out>/ltca.md``, ``summary.json`` and ``stiffness_vs_torque.png``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
from pathlib import Path


from pipelines.cases.reader import load_case
from pipelines.cases.ltca import read_ltca_case
from pipelines.models.ltca.run import TARGETS, build_model, check_indices, fe_check, positions, solve_positions

__all__ = ["main"]

CASE = Path(__file__).resolve().parents[1] / "cases" / "ltca_pair_small.toml"
SWEEP_NM = (20.0, 40.0, 78.0, 117.0, 156.0, 234.0, 312.0, 468.0)
FE_SWEEP_NM = (40.0, 156.0, 468.0)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", default="out/bench/ltca")
    ap.add_argument("--checks", type=int, default=6)
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    case, opts = read_ltca_case(load_case(CASE))
    T = case.torque
    load0 = os.getloadavg()[0]
    c0 = time.process_time()
    model = build_model(case, opts, print)
    build_cpu = time.process_time() - c0
    phis = positions(model)
    t0, c0 = time.perf_counter(), time.process_time()
    rows, _, timing = solve_positions(model, phis, (T,))
    t_pos, cpu_pos = time.perf_counter() - t0, time.process_time() - c0
    _, _, timing2 = solve_positions(model, phis[:20], (T, 0.5 * T))
    print(f"build {model.build_s:.1f} s (cpu {build_cpu:.1f} s), {len(phis)} positions {t_pos:.2f} s (cpu {cpu_pos:.2f} s)")
    idx = check_indices(rows, args.checks)
    check = fe_check(model, rows, idx, None, print)
    # torque sweep where a second pair closes under load
    one = [i for i, r in enumerate(rows) if r["pairs_loaded"] == 1]
    # the single-pair position next to the end of the single-pair zone (the next pair closes first there)
    j = max(one) if one else 0
    phi = phis[j]
    sweep, _, _ = solve_positions(model, [phi], tuple(t * 1e3 for t in SWEEP_NM))
    fe_rows = [r for r in sweep if r["torque_nm"] in FE_SWEEP_NM]
    fe_sw = fe_check(model, fe_rows, list(range(len(fe_rows))), None, print)
    _plot(sweep, fe_sw, out / "stiffness_vs_torque.png", math.degrees(phi))
    rec = {"case": CASE.name, "load_at_start": load0, "build_s": model.build_s, "build_cpu_s": build_cpu,
           "flanks": {fc.gear.name: fc.info for fc in model.flanks}, "sizes_mm": model.sizes,
           "positions": len(phis), "positions_s": t_pos, "positions_cpu_s": cpu_pos, "timing": timing,
           "timing_two_torques": timing2, "fe_check": check, "sweep_phi1_deg": math.degrees(phi),
           "sweep": [{k: r[k] for k in ("torque_nm", "mesh_stiffness_n_per_um", "pairs_loaded", "elastic_rotation_arcsec")}
                     | {k: v for k, v in r.items() if k.startswith("share.")} for r in sweep],
           "fe_sweep": fe_sw["positions"]}
    (out / "summary.json").write_text(json.dumps(rec, indent=2, default=float) + "\n")
    (out / "ltca.md").write_text(_report(rec))
    print(f"wrote {out / 'ltca.md'}")
    return 0


def _plot(sweep, fe_sw, path, phi_deg):
    from pipelines.render.plots import plt, savefig

    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot([r["torque_nm"] for r in sweep], [r["mesh_stiffness_n_per_um"] for r in sweep], "o-", label="loaded TCA")
    ax.plot([p["torque_nm"] for p in fe_sw["positions"]], [p["fe_mesh_stiffness_n_per_um"] for p in fe_sw["positions"]],
            "s--", label="full contact FE")
    ax.set_xlabel("torque on the driven gear [N m]")
    ax.set_ylabel("mesh stiffness [N/um]")
    ax.set_title(f"Mesh stiffness vs torque at phi1 = {phi_deg:.3f} deg")
    ax.grid(alpha=0.3)
    ax.legend()
    savefig(fig, path)


def _report(r: dict) -> str:
    t = r["timing"]
    c = r["fe_check"]
    lines = ["# Loaded TCA (issue 18): speed and accuracy", "",
             f"Case `{r['case']}`; load average {r['load_at_start']:.2f} at the start (2 cores shared: wall times vary).", "",
             "## Speed", "",
             "| stage | wall [s] | target |", "|---|---|---|",
             f"| build (TCA + both flank compliances) | {r['build_s']:.1f} (cpu {r['build_cpu_s']:.1f}) | <= 60 |",
             f"| {r['positions']} positions, one torque | {r['positions_s']:.2f} (cpu {r['positions_cpu_s']:.2f}) | <= 30 |",
             f"| a further position (lines + one solve) | {t['per_position_s']:.4f} | |",
             f"| a further torque, per position | {r['timing_two_torques']['per_torque_per_position_s']:.4f} | |", "",
             "Flank models: " + ", ".join(f"{g}: {i['elements']} elements, {i['dofs']} DOF, {i['flank_nodes']} flank nodes, "
                                           f"{i['total_s']:.1f} s" for g, i in r["flanks"].items()), "",
             "## Accuracy against the full contact FE (`gearfe stress`, same case)", "",
             "| phi1 [deg] | rotation FE / LTCA [arcsec] | error | share error | p_max FE / LTCA [MPa] | error |",
             "|---|---|---|---|---|---|"]
    for p in c["positions"]:
        lines.append(f"| {p['phi1_deg']:.3f} | {p['fe_elastic_rotation_arcsec']:.2f} / {p['ltca_elastic_rotation_arcsec']:.2f} | "
                     f"{p['rotation_error']:.3f} | {p['share_error']:.3f} | {p['fe_peak_pressure_mpa']:.0f} / "
                     f"{p['ltca_peak_pressure_mpa']:.0f} | {p['pressure_error']:.3f} |")
    lines += ["", "| quantity | worst | target | met |", "|---|---|---|---|"]
    for k in TARGETS:
        lines.append(f"| {k} | {c['worst'][k]:.4f} | {TARGETS[k]} | {'yes' if c['met'][k] else 'NO'} |")
    lines += ["", f"## Torque sweep at phi1 = {r['sweep_phi1_deg']:.3f} deg", "",
              "| torque [N m] | LTCA k [N/um] | pairs loaded |", "|---|---|---|"]
    lines += [f"| {s['torque_nm']:g} | {s['mesh_stiffness_n_per_um']:.1f} | {s['pairs_loaded']} |" for s in r["sweep"]]
    lines += ["", "| torque [N m] | FE k [N/um] | LTCA k [N/um] | FE shares |", "|---|---|---|---|"]
    lines += [f"| {p['torque_nm']:g} | {p['fe_mesh_stiffness_n_per_um']:.1f} | {p['ltca_mesh_stiffness_n_per_um']:.1f} | "
              f"{', '.join(f'{k} {v:.3f}' for k, v in p['fe_shares'].items())} |" for p in r["fe_sweep"]]
    lines += ["", "![stiffness](stiffness_vs_torque.png)", ""]
    return "\n".join(lines)


if __name__ == "__main__":
    raise SystemExit(main())
