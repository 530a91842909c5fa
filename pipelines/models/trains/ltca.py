"""``gearfe ltca`` of a planetary train: layout, model, the run of every torque, files and summary.

``run_train_ltca(case, out)`` writes into ``out``:

- ``results.csv``: one row per torque and position: carrier and sun angles [deg], loaded TE [arcsec], each
  planet's share of the sun mesh and of the ring mesh (``sun_share.p<i>``, ``ring_share.p<i>``), each member's
  share of the sun mesh for twins (``member_share.p<i><k>``), the sun centre [um] (fixed frame), each mesh's
  normal force [N] and peak pressure [MPa] (``force.<mesh>``, ``pressure.<mesh>``);
- ``planet_shares.png``, ``te_train.png``, ``sun_center.png`` (where the sun moves) and ``report.html``;
- the summary (``summary.json`` by the CLI): ``k_gamma``, ``k_gamma_members`` (twins), ``planet_shares``
  (per planet min, mean, max), the planets without load at some positions, the conventions
  (:data:`pipelines.models.trains.run.CONVENTIONS`), build and solve times, the cost of a further position and
  torque.
"""

from __future__ import annotations

import csv
import math
import time
from pathlib import Path

import numpy as np

from tca.planetary.regulation import RegulationOptions, regulate_train
from tca.planetary.train import dz_first_order
from tca.planetary.regulation import member_d_ex
from tca.units import ARCSEC

from pipelines.models.trains.case import TrainCase
from pipelines.models.trains.geometry import TrainLayout, double_helical_layout, single_layout
from pipelines.models.trains.model import build_train_model
from pipelines.models.trains.run import CONVENTIONS, TrainRun, solve_run, train_positions
from pipelines.render.html import image, section, table, write_page
from pipelines.render.trains import plot_compare_trains, plot_train_ltca

__all__ = ["train_layout", "run_train_ltca", "regulation_dz", "compare_trains"]


def regulation_dz(case: TrainCase, say=None) -> tuple:
    """The axial regulation (ΔZ_a, ΔZ_b) [mm] of every shaft of a Part 1 train for ``case.opts.regulation``."""
    tr, errs = case.twin, case.shaft_errors
    mode = case.opts.regulation
    if mode == "none" or all(e.d_ex == 0.0 and e.d_gamma == 0.0 for e in errs):
        return tuple((0.0, 0.0) for _ in errs)
    if mode == "first_order":
        return tuple((dz_first_order(tr, member_d_ex(tr, "a", e)), dz_first_order(tr, member_d_ex(tr, "b", e)))
                     for e in errs)
    ro = case.regulation
    reg = regulate_train(tr, errs, case.opts.tca, RegulationOptions(ro.tol, ro.max_iterations),
                         progress=(lambda m: say(f"regulation: {m}")) if say else None)
    return tuple((a.dz2, b.dz2) for a, b in reg.members)


def train_layout(case: TrainCase, say=None) -> tuple[TrainLayout, tuple]:
    """The layout of the case's train and the regulation used ((0, 0) per shaft for isostatic trains)."""
    if case.kind == "planetary":
        dz = regulation_dz(case, say)
        return double_helical_layout(case.twin, case.shaft_errors, dz, case.opts.regulation != "none"), dz
    return single_layout(case.sun, case.planet, case.ring, case.planets), ()


def _rows(run: TrainRun, layout: TrainLayout) -> list:
    rows = []
    mc = layout.carrier_ratio
    twin = len(layout.members) > 1
    for j in range(len(run.psi1)):
        r = {"torque_nm": run.torque * 1e-3, "carrier_deg": math.degrees(run.carrier[j]),
             "sun_deg": math.degrees(run.psi1[j] / (1 - mc)), "te_loaded_arcsec": run.te[j] / ARCSEC}
        for i in range(run.planets):
            r[f"sun_share.p{i + 1}"] = run.sun_share[j, i]
            r[f"ring_share.p{i + 1}"] = run.ring_share[j, i]
            if twin:
                for k, m in enumerate(layout.members):
                    r[f"member_share.p{i + 1}{m}"] = run.member_share[j, i, k]
        r["sun_x_um"], r["sun_y_um"] = run.sun_center[j] * 1e3
        for m, s in enumerate(layout.sites):
            r[f"force.{s.name}"] = run.mesh_force[j, m]
            r[f"pressure.{s.name}"] = run.peak_pressure[j, m]
        rows.append(r)
    return rows


def _write_csv(path: Path, rows: list) -> None:
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.9g}" if isinstance(v, float) else v) for k, v in r.items()})


def _run_summary(run: TrainRun, layout: TrainLayout) -> dict:
    s = {"torque_nm": run.torque * 1e-3, "k_gamma": run.k_gamma, "planet_shares": run.shares_summary(),
         "te_loaded_peak_to_peak_arcsec": float(np.ptp(run.te) / ARCSEC),
         "te_loaded_mean_arcsec": float(run.te.mean() / ARCSEC),
         "peak_pressure_mpa": {s.name: float(run.peak_pressure[:, m].max()) for m, s in enumerate(layout.sites)},
         "unloaded_planets": [{"planet": i, "positions": k} for i, k in run.unloaded]}
    if len(layout.members) > 1:
        s["k_gamma_members"] = run.k_gamma_members
        s["member_shares"] = {f"p{i + 1}{m}": {"min": float(run.member_share[:, i, k].min()),
                                               "mean": float(run.member_share[:, i, k].mean()),
                                               "max": float(run.member_share[:, i, k].max())}
                              for i in range(run.planets) for k, m in enumerate(layout.members)}
    if np.abs(run.sun_center).max() > 0:
        c = run.sun_center * 1e3
        s["sun_center_um"] = {"mean": c.mean(0).tolist(), "max_offset": float(np.linalg.norm(c, axis=1).max())}
    return s


def run_train_ltca(case: TrainCase, out: Path, say=None, bar=None, runs: list | None = None) -> dict:
    """Build the train's model, solve every torque over the run, write the files (module docstring); the summary."""
    t0 = time.perf_counter()
    layout, dz = train_layout(case, say)
    model = build_train_model(layout, case.opts, say)
    model.build_phases()  # the slices of every mesh phase, once (a position then costs its coupled solve)
    t_build = time.perf_counter() - t0
    psi1 = train_positions(model)
    if say is not None:
        say(f"{len(psi1)} positions over {case.opts.carrier_revolutions:g} carrier revolution(s), "
            f"{len(layout.sites)} meshes, {len(case.opts.torques)} torque(s)")
    keep, runs, rows = runs, [], []
    t1 = time.perf_counter()
    for T in case.opts.torques:
        r = solve_run(model, case.errors, T, psi1, bar)
        runs.append(r)
        if keep is not None:
            keep.append(r)
        rows += _rows(r, layout)
    t_solve = time.perf_counter() - t1
    out = Path(out)
    _write_csv(out / "results.csv", rows)
    files = ["results.csv"] + plot_train_ltca(runs, out, case.title)
    per_torque = [_run_summary(r, layout) for r in runs]
    slices = sum(r.build_slices_s for r in runs)
    solves = sum(r.solve_s for r in runs)
    J = len(psi1)
    summary = {
        "kind": case.kind, "title": case.title, "planets": layout.planets, "members": list(layout.members),
        "teeth": list(layout.teeth), "sun_axis": case.opts.sun_axis,
        "sun_support_n_per_um": None if case.opts.sun_support is None else case.opts.sun_support * 1e-3,
        "pin_stiffness_n_per_um": None if case.opts.pin_stiffness is None else case.opts.pin_stiffness * 1e-3,
        "regulation": case.opts.regulation if case.kind == "planetary" else None,
        "regulation_dz_mm": [list(d) for d in dz],
        "k_gamma": max(p["k_gamma"] for p in per_torque),
        "planet_shares": per_torque[0]["planet_shares"], "planet_shares_torque_nm": per_torque[0]["torque_nm"],
        "torques": per_torque, "conventions": CONVENTIONS,
        "positions": J, "meshes": len(layout.sites), "build": model.build, "build_s": t_build,
        "solve_all_s": t_solve,
        "timing": {"positions": J, "torques": len(runs), "slices_s": slices, "coupled_solve_s": solves,
                   "per_position_s": (slices + solves) / max(J * len(runs), 1),
                   "per_torque_per_position_s": solves / max(J * len(runs), 1),
                   "distinct_mesh_phases": model.cached_phases},
        "files": files,
    }
    if len(layout.members) > 1:
        summary["k_gamma_members"] = max(p["k_gamma_members"] for p in per_torque)
    rep = [section("Load sharing", table([{"torque_nm": p["torque_nm"], "k_gamma": p["k_gamma"],
                                           "k_gamma_members": p.get("k_gamma_members", ""),
                                           "te_p2p_arcsec": p["te_loaded_peak_to_peak_arcsec"],
                                           "unloaded": str(p["unloaded_planets"] or "none")} for p in per_torque])),
           section("Planet shares", table(per_torque[0]["planet_shares"]),
                   image(out / "planet_shares.png", "Planet shares of the sun and ring meshes against the carrier "
                         "angle")),
           section("Loaded TE of the train", image(out / "te_train.png", CONVENTIONS["loaded_te"]))]
    if "sun_center.png" in files:
        rep.append(section("Sun centre", image(out / "sun_center.png", CONVENTIONS["sun_center"])))
    rep.append(section("Conventions", table([{"quantity": k, "convention": v} for k, v in CONVENTIONS.items()])))
    write_page(out / "report.html", f"Loaded TCA of the train: {case.title}", *rep)
    summary["files"] = files + ["report.html"]
    return summary


def compare_trains(cases: dict, out: Path, say=None, bar=None) -> dict:
    """Two trains side by side (``cases``: label -> TrainCase, e.g. regulated against not, floating against fixed
    sun): each run into ``out/<label>``, then ``compare_shares.png``, ``compare.json`` rows and ``report.html``."""
    out = Path(out)
    runs, summaries = {}, {}
    for label, c in cases.items():
        (out / label).mkdir()
        kept = []
        summaries[label] = run_train_ltca(c, out / label, say, bar, kept)
        runs[label] = kept[0]
    png = plot_compare_trains(runs, out)
    rows = [{"train": label, "title": s["title"], "sun_axis": s["sun_axis"], "regulation": s["regulation"] or "",
             "torque_nm": s["torques"][0]["torque_nm"], "k_gamma": s["torques"][0]["k_gamma"],
             "k_gamma_members": s["torques"][0].get("k_gamma_members", ""),
             "min_share": min(p["sun_min"] for p in s["planet_shares"]),
             "max_share": max(p["sun_max"] for p in s["planet_shares"]),
             "te_p2p_arcsec": s["torques"][0]["te_loaded_peak_to_peak_arcsec"],
             "unloaded_planets": len(s["torques"][0]["unloaded_planets"])} for label, s in summaries.items()]
    (a, ra), (b, rb) = runs.items()
    better = a if ra.k_gamma < rb.k_gamma else b
    finding = (f"{better} shares the load more evenly: K_gamma {min(ra.k_gamma, rb.k_gamma):.4f} against "
               f"{max(ra.k_gamma, rb.k_gamma):.4f}")
    write_page(out / "report.html", "Two trains under load", section("Load sharing", table(rows)),
               section("Finding", f"<p>{finding}</p>"),
               image(out / png, "n x the largest planet share against the carrier angle, both trains"),
               section("Conventions", table([{"quantity": k, "convention": v} for k, v in CONVENTIONS.items()])))
    return {"rows": rows, "finding": finding, "files": [png, "report.html", "compare.json"] +
            [f"{k}/{f}" for k, s in summaries.items() for f in s["files"]], "summaries": summaries}
