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
``delta_scan.csv`` (peak-to-peak TE against delta) and the figures of the report: ``fig2_3_subdrives.png``,
``fig2_4_integrated.png`` (``fig2_8`` for the multiplier), ``fig2_5_contact_paths.png``,
``fig2_6_delta_cases.png``, ``fig2_7_particular_cases.png`` (``fig2_9``), ``te_vs_delta.png``.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from tca.face.subgear import ARCSEC  # noqa: E402
from tca.face.train import (FaceTrain, FaceTrainResult, basic_ratio, run_face_train, scan_delta,  # noqa: E402
                            stage_results, te_peak_to_peak, train_efficiency, train_ratio)

from pipelines.cases.face import read_face_train  # noqa: E402
from pipelines.render.plots import savefig  # noqa: E402
from pipelines.cases.schema import Table  # noqa: E402

__all__ = ["run"]

_BRANCH = {-1: "forward", 0: "middle", 1: "backward"}



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
                        _BRANCH.get(int(r.pair_b[i]), str(int(r.pair_b[i]))), int(r.edge[i])])


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


# ------------------------------------------------------------------------------------------ plots
def _te_axes(ax, r: FaceTrainResult, te_name: str, name_in: str, label: bool = True):
    x = np.degrees(r.phi_in)
    te = r.te_arcsec - r.te_arcsec.max()  # as the report: the maximum at zero
    for jb, color in ((-1, "C2"), (0, "C0"), (1, "C3")):
        m = r.pair_b == jb
        if m.any():
            y = np.where(m, te, np.nan)
            ax.plot(x, y, color=color, lw=2, label=f"{_BRANCH[jb]} pair of sub-drive 2" if label else None)
    if r.edge.any():
        ax.plot(x[r.edge], te[r.edge], "o", ms=3, color="k", label="edge contact" if label else None)
    ax.set_xlabel(rf"$\phi_{{{name_in[-1]}}}$ [deg]")
    ax.set_ylabel(rf"${te_name}$ [arcsec]")
    ax.grid(alpha=0.3)


def plot_subdrives(ra, rb, cycles: int, path: Path) -> Path:
    """Fig. 2.3: TE of the two sub-drives over the cycles (pair in contact thick, neighbours thin)."""
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for ax, r, k in ((axes[0], ra, 1), (axes[1], rb, 2)):
        ph, te, j, kind = r.te_cycles(cycles, 60)
        T, Tn = r.mesh.pitches
        base = r.te_ref / ARCSEC
        for jj in range(-1, cycles + 1):
            xx = r.phi + jj * T
            sel = (xx >= ph[0] - 1e-12) & (xx <= ph[-1] + 1e-12)
            ax.plot(np.degrees(xx[sel]), base[sel] + (jj * Tn - r.mesh.ratio * jj * T) / ARCSEC, color="0.75", lw=0.8)
        ax.plot(np.degrees(ph), te / ARCSEC, color="C0", lw=2)
        if np.any(kind != 1):
            ax.plot(np.degrees(ph[kind != 1]), te[kind != 1] / ARCSEC, "o", ms=3, color="C3", label="edge contact")
            ax.legend(fontsize=8)
        dr, dn = (r.mesh.face.name, r.mesh.pinion.name) if r.mesh.driver == "face" else (r.mesh.pinion.name, r.mesh.face.name)
        ax.set_title(f"sub-drive {k}: {dr} drives {dn}")
        ax.set_xlabel(f"{dr} angle [deg]")
        ax.set_ylabel(f"TE of {dn} [arcsec]")
        span = te.max() - te.min()
        ax.set_ylim((te.min() / ARCSEC) - 0.3 * span / ARCSEC, (te.max() / ARCSEC) + 0.15 * span / ARCSEC)
        ax.grid(alpha=0.3)
    fig.suptitle("Transmission errors of the sub-drives (Fig. 2.3)")
    return savefig(fig, path)


def plot_integrated(r: FaceTrainResult, path: Path, te_name: str, name_in: str, title=None) -> Path:
    """Fig. 2.4 / 2.8: integrated TE over the cycles, branches by the pair of sub-drive 2."""
    fig, ax = plt.subplots(figsize=(8, 4.2))
    _te_axes(ax, r, te_name, name_in)
    ax.set_title(title or f"delta = {r.train.delta:.5f} rad: {r.te_peak_to_peak_arcsec:.2f} arcsec, "
                          f"{r.branches_per_cycle} branch(es) per cycle")
    ax.legend(fontsize=8, loc="lower right")
    return savefig(fig, path)


def plot_delta_cases(cases: dict, delta0: float, path: Path, te_name: str, name_in: str) -> Path:
    """Fig. 2.6: integrated TE for several installation angles."""
    n = len(cases)
    cols = 2 if n > 1 else 1
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(6 * cols, 3.4 * rows), squeeze=False)
    for ax, (off, r) in zip(axes.ravel(), cases.items()):
        _te_axes(ax, r, te_name, name_in, label=False)
        ax.set_title(f"delta = {delta0:.5f} {off:+.4f} rad: {r.te_peak_to_peak_arcsec:.2f} arcsec", fontsize=9)
    for ax in axes.ravel()[n:]:
        ax.axis("off")
    fig.tight_layout()
    return savefig(fig, path)


def plot_particular(single: FaceTrainResult, best: FaceTrainResult, delta0: float, path: Path, te_name: str,
                    name_in: str) -> Path:
    """Fig. 2.7 / 2.9: (a) one branch per cycle (transitions aligned), (b) the optimal delta."""
    fig, axes = plt.subplots(1, 2, figsize=(12, 4))
    for ax, r, lab in ((axes[0], single, "(a) one branch"), (axes[1], best, "(b) optimal delta")):
        _te_axes(ax, r, te_name, name_in, label=False)
        ax.set_title(f"{lab}: delta = {delta0:.5f} {r.train.delta - delta0:+.5f} rad, "
                     f"{r.te_peak_to_peak_arcsec:.2f} arcsec", fontsize=9)
    fig.tight_layout()
    return savefig(fig, path)


def plot_scan(scan, delta0: float, path: Path) -> Path:
    """Peak-to-peak integrated TE against the installation angle, with the particular angles."""
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(scan.delta - delta0, scan.te_pp / ARCSEC, "-", color="C0")
    for d, t, lab, c in ((scan.delta_single, scan.te_single, "one branch", "C3"), (scan.delta_equal, scan.te_equal,
                         "equal branches", "C2"), (scan.delta_opt, scan.te_opt, "optimum", "k")):
        ax.plot([d - delta0], [t / ARCSEC], "o", color=c, label=f"{lab}: {d - delta0:+.4f} rad, {t / ARCSEC:.2f} arcsec")
    ax.set_xlabel(f"delta - {delta0:.5f} [rad]")
    ax.set_ylabel("peak-to-peak integrated TE [arcsec]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return savefig(fig, path)


def plot_contact_paths(ra, rb, path: Path) -> Path:
    """Fig. 2.5: paths of contact on the pinions (z, radius) and on the face gears (radius L, height)."""
    fig, axes = plt.subplots(2, 2, figsize=(11, 7))
    for row, r in enumerate((ra, rb)):
        ph = np.append(np.linspace(r.phi_min, r.phi_max, 41)[:-1], r.phi_max - 1e-9)  # one pair, one cycle
        cp = r.contact_points(ph)
        pin, face = cp["pinion"], cp["face"]
        edge = cp["kind"] != 1
        ax = axes[row, 0]
        p = r.mesh.pinion
        ar = p.area(1 if r.mesh.driver == "pinion" else -1)
        ax.add_patch(plt.Rectangle((ar.z_min, ar.r_form), ar.z_max - ar.z_min, ar.r_tip - ar.r_form, fill=False, ec="0.4"))
        ax.plot(pin[:, 2], np.hypot(pin[:, 0], pin[:, 1]), ".-", color="C0", ms=3)
        ax.plot(pin[edge, 2], np.hypot(pin[edge, 0], pin[edge, 1]), "o", color="C3", ms=4)
        ax.set_title(f"{p.name} ({'+y' if r.mesh.driver == 'pinion' else '-y'} flank)", fontsize=9)
        ax.set_xlabel("z [mm]")
        ax.set_ylabel("radius [mm]")
        ax.grid(alpha=0.3)
        ax = axes[row, 1]
        g = r.mesh.face
        rho, _, xe = g.cone_coords(face)
        ax.axvline(g.L1, color="0.4")
        ax.axvline(g.L2, color="0.4")
        ax.axhline(g.x_tip, color="0.4", ls="--")
        ax.plot(rho, xe, ".-", color="C0", ms=3)
        ax.plot(rho[edge], xe[edge], "o", color="C3", ms=4)
        ax.set_title(f"{g.name} ({'-y' if r.mesh.driver == 'pinion' else '+y'} flank): L1 = {g.L1:.2f}, "
                     f"L2 = {g.L2:.2f} mm", fontsize=9)
        ax.set_xlabel("distance from the face-gear axis L [mm]")
        ax.set_ylabel("height x_eq [mm] (tip cone dashed)")
        ax.grid(alpha=0.3)
    fig.suptitle("Paths of contact over one cycle, no errors of alignment (Fig. 2.5); red: edge contact")
    fig.tight_layout()
    return savefig(fig, path)
