"""TCA of the planetary train with face gears (kind = "face_train"), Part 2 of the report.

Case keys (see ``pipelines/cases/part2_reducer.toml``)::

    kind = "face_train"
    use = "reducer"              # inverted train driven by face gear 4 (TE dphi_14) | "multiplier" (by gear 1, dphi_41)
    delta_rad = 0.18479957       # installation angle of pinion 2 relative to pinion 3 (pi/17)
    loss_per_mesh = 0.02         # power loss per mesh for the efficiency (Example 2.1)
    [train]                      # planetary use for ratio and efficiency: members gear1 | gear4 | carrier
    fixed = "gear4"; input = "carrier"; output = "gear1"
    [shaper]                     # gear keys of pipelines.cases.reader (teeth, module_mm, ..., addendum, tool_addendum)
    [gear1] / [gear4]            # teeth, shaft_angle_deg, crowning_per_mm, addendum, pinion_addendum,
                                 # inner_radius_mm, outer_radius_mm (default: limits of undercutting / pointing)
    [pinion2] / [pinion3]        # gear keys of pipelines.cases.reader
    [tca]                        # cycles, steps_per_cycle, mesh_steps_per_cycle, delta_samples
    [plots]                      # delta_offsets_rad: the installation angles of Fig. 2.6 relative to delta_rad

Writes ``face_train.csv`` (integrated TE per position), ``subdrives.csv`` (TE of each sub-drive),
``delta_scan.csv`` (peak-to-peak TE against delta) and the figures of the report (:mod:`pipelines.render.face`):
``fig2_3_subdrives.png``, ``fig2_4_integrated.png`` (``fig2_8`` for the multiplier), ``fig2_5_contact_paths.png``,
``fig2_6_delta_cases.png``, ``fig2_7_particular_cases.png`` (``fig2_9``), ``te_vs_delta.png``.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

from tca.face.subgear import ARCSEC
from tca.face.train import (FaceTrain, FaceTrainResult, basic_ratio, run_face_train, scan_delta, stage_results,
                            te_peak_to_peak, train_efficiency, train_ratio)

from pipelines.cases.face import read_face_train
from pipelines.cases.schema import Table
from pipelines.render.face import (BRANCH_NAMES, plot_contact_paths, plot_delta_cases, plot_integrated, plot_particular,
                                   plot_scan, plot_subdrives)

__all__ = ["run"]


def run(case: Table, out: Path) -> dict:
    train, o = read_face_train(case)
    fixed, driver, driven = o["members"]
    n1, n2, n3, n4 = train.teeth
    ratio = train_ratio(n1, n2, n3, n4, fixed, driver, driven)
    eff = train_efficiency(n1, n2, n3, n4, o["loss"], fixed, driver, driven)
    ra, rb = stage_results(train, o["mesh_steps_per_cycle"])
    res = run_face_train(train, o["cycles"], o["steps_per_cycle"], stages=(ra, rb))
    scan = scan_delta(train, ra, rb, samples=o["delta_samples"])
    cases = {off: run_face_train(FaceTrain(train.gear1, train.gear4, train.pinion2, train.pinion3, train.delta + off,
                                           train.use), o["cycles"], o["steps_per_cycle"], stages=(ra, rb))
             for off in o["delta_offsets"]}
    single = run_face_train(_with_delta(train, scan.delta_single), o["cycles"], o["steps_per_cycle"], stages=(ra, rb))
    best = run_face_train(_with_delta(train, scan.delta_opt), o["cycles"], o["steps_per_cycle"], stages=(ra, rb))
    mult = train.use == "multiplier"

    def pp(delta):  # peak-to-peak over one cycle, exact solves (240 positions and the cusps) [arcsec]
        return te_peak_to_peak(train, ra, rb, delta, samples=240, exact=True) / ARCSEC

    name_in, name_out = ("gear1", "gear4") if mult else ("gear4", "gear1")
    te_name = r"\Delta\phi_{41}" if mult else r"\Delta\phi_{14}"
    title = case.get("title", str, "")
    files = ["summary.json", "face_train.csv", "subdrives.csv", "delta_scan.csv"]
    _write_train_csv(res, out / "face_train.csv")
    _write_subdrives_csv(ra, rb, o["cycles"], out / "subdrives.csv")
    _write_scan_csv(scan, out / "delta_scan.csv")
    f_int = "fig2_8_integrated.png" if mult else "fig2_4_integrated.png"
    f_par = "fig2_9_particular_cases.png" if mult else "fig2_7_particular_cases.png"
    plot_subdrives(ra, rb, o["cycles"], out / "fig2_3_subdrives.png")
    plot_integrated(res, out / f_int, te_name, name_in, title or None)
    plot_contact_paths(ra, rb, out / "fig2_5_contact_paths.png")
    plot_delta_cases(cases, train.delta, out / "fig2_6_delta_cases.png", te_name, name_in)
    plot_particular(single, best, train.delta, out / f_par, te_name, name_in)
    plot_scan(scan, train.delta, out / "te_vs_delta.png")
    files += ["fig2_3_subdrives.png", f_int, "fig2_5_contact_paths.png", "fig2_6_delta_cases.png", f_par,
              "te_vs_delta.png"]
    pitch2 = 2 * math.pi / n2
    amp = {}
    for r in (ra, rb):
        ph, te, _, _ = r.te_cycles(1, 120)
        amp[f"{r.mesh.face.name}_{r.mesh.pinion.name}"] = {
            "driver": r.mesh.driver, "te_peak_to_peak_arcsec_of_driven": float((te.max() - te.min()) / ARCSEC),
            "edge_contact_fraction": r.edge_fraction, "working_area_margins_mm": r.margins,
            "phi_min_deg": math.degrees(r.phi_min), "phi_max_deg": math.degrees(r.phi_max)}
    return {
        "use": train.use,
        "members": {"fixed": fixed, "input": driver, "output": driven},
        "teeth": {"N1": n1, "N2": n2, "N3": n3, "N4": n4},
        "ratio": ratio,
        "ratio_inverted_train": basic_ratio(n1, n2, n3, n4),
        "efficiency": eff,
        "loss_per_mesh": o["loss"],
        "te": f"{'dphi_41' if mult else 'dphi_14'}: output {name_out} minus ideal, arcsec of {name_out}, peak-to-peak",
        "delta_rad": train.delta,
        "delta_minus_half_pitch_rad": train.delta - pitch2 / 2,
        "te_max_arcsec": pp(train.delta),
        "branches_per_cycle": res.branches_per_cycle,
        "branch_fractions": res.branch_fractions.tolist(),
        "edge_contact": bool(res.edge.any()),
        "delta_opt_rad": scan.delta_opt,
        "delta_opt_minus_half_pitch_rad": scan.delta_opt - pitch2 / 2,
        "te_max_opt_arcsec": scan.te_opt_exact / ARCSEC,
        "branches_per_cycle_opt": best.branches_per_cycle,
        "branch_fractions_opt": best.branch_fractions.tolist(),
        "delta_single_rad": scan.delta_single,
        "delta_single_minus_half_pitch_rad": scan.delta_single - pitch2 / 2,
        "te_single_arcsec": pp(scan.delta_single),
        "delta_equal_rad": scan.delta_equal,
        "delta_equal_minus_half_pitch_rad": scan.delta_equal - pitch2 / 2,
        "te_equal_arcsec": pp(scan.delta_equal),
        "te_max_over_delta_arcsec": max(float(scan.te_pp.max() / ARCSEC), pp(scan.delta_single)),
        "te_min_over_delta_scan_arcsec": float(scan.te_pp.min() / ARCSEC),
        "delta_cases": {f"{off:+.4f}": {"te_max_arcsec": pp(r.train.delta), "branches_per_cycle": r.branches_per_cycle}
                        for off, r in cases.items()},
        "face_gears": {g.name: {"L1_mm": g.L1, "L2_mm": g.L2, "L1_undercut_mm": g.limits.L1_undercut,
                                "L1_fillet_mm": g.limits.L1_fillet, "L2_pointing_mm": g.limits.L2_pointing,
                                "pitch_radius_mm": g.pitch_radius, "top_land_at_pitch_mm": g.limits.top_land_at_pitch,
                                "fit_error_mm": max(g.surface(s).fit_error for s in (1, -1))}
                       for g in (train.gear1, train.gear4)},
        "subdrives": amp,
        "transitions_rad": {k: float(v) for k, v in res.transitions.items()},
        "apex_distances_mm": {m.face.name: m.apex_distance for m in train.meshes()},
        "positions": int(len(res.phi_in)),
        "cycles": o["cycles"],
        "files": files,
    }


def _with_delta(train: FaceTrain, delta: float) -> FaceTrain:
    from dataclasses import replace

    return replace(train, delta=delta)


# ------------------------------------------------------------------------------------------ files
def _write_train_csv(r: FaceTrainResult, path: Path) -> None:
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["phi_in_deg", "phi_p_deg", "phi_out_deg", "te_arcsec", "pair_subdrive1", "pair_subdrive2",
                    "branch", "edge_contact"])
        for i in range(len(r.phi_in)):
            w.writerow([f"{math.degrees(r.phi_in[i]):.9f}", f"{math.degrees(r.phi_p[i]):.9f}",
                        f"{math.degrees(r.phi_out[i]):.9f}", f"{r.te_arcsec[i]:.6f}", int(r.pair_a[i]), int(r.pair_b[i]),
                        BRANCH_NAMES.get(int(r.pair_b[i]), str(int(r.pair_b[i]))), int(r.edge[i])])


def _write_subdrives_csv(ra, rb, cycles: int, path: Path) -> None:
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["subdrive", "face_gear", "driver", "phi_driver_deg", "te_arcsec_of_driven", "pair", "edge_contact"])
        for k, r in ((1, ra), (2, rb)):
            ph, te, j, kind = r.te_cycles(cycles, 60)
            for i in range(len(ph)):
                w.writerow([k, r.mesh.face.name, r.mesh.driver, f"{math.degrees(ph[i]):.9f}", f"{te[i] / ARCSEC:.6f}",
                            int(j[i]), int(kind[i] != 1)])


def _write_scan_csv(scan, path: Path) -> None:
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["delta_rad", "te_peak_to_peak_arcsec"])
        for d, t in zip(scan.delta, scan.te_pp):
            w.writerow([f"{d:.9f}", f"{t / ARCSEC:.6f}"])
