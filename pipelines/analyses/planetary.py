"""TCA of the double-helical planetary train (kind = "planetary"): regulation and integrated TE (Part 1).

Case keys: ``planets`` (n), ``member_gap_mm`` (F), gears ``[gears.sun]``, ``[gears.planet]``,
``[gears.ring]`` (members *a*; members *b* are their mirror images), ``[installment]`` with lists of
n values ``d_ex_um`` (ΔE_x, positive against the sun's rotation) and ``d_gamma_arcmin`` (Δγ about
the radial line through the shaft centre), ``[regulation]`` ``tol_arcsec``, ``max_iterations``,
and ``[tca]`` (``steps_per_cycle`` a multiple of n). Writes ``summary.json`` (``regulation`` per
planet, spreads), ``te.csv``, ``fig14_te.png`` (Fig. 1.4(a)/(b)), ``fig14c_contact_paths.png``
and, when a shaft has Δγ, ``fig15_members.png`` (Fig. 1.5); the figures are drawn by
:mod:`pipelines.render.planetary`.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from tca.pair.analysis import ARCSEC
from tca.planetary.regulation import RegulationOptions, TrainRegulation, member_d_ex, periodic_peak, regulate_train

from pipelines.cases.planetary import read_installment, read_regulation_options, read_train
from pipelines.cases.reader import ARCMIN, read_tca_options
from pipelines.cases.schema import Table
from pipelines.render.planetary import plot_members, plot_train_te, plot_twin_contact_paths

__all__ = ["run"]



def run(case: Table, out: Path) -> dict:
    train = read_train(case)
    errors = read_installment(case.table("installment", required=False), train.planets)
    ro = read_regulation_options(case.table("regulation", required=False))
    opts = read_tca_options(case.table("tca", required=False))
    title = case.get("title", str, "")
    reg = regulate_train(train, errors, opts, RegulationOptions(ro.tol, ro.max_iterations),
                         progress=lambda m: print(f"  {m}", flush=True))

    write_te_csv(reg, out / "te.csv")
    plot_train_te(reg, out / "fig14_te.png", title)
    tilted = [i for i, e in enumerate(errors) if e.d_gamma != 0.0]
    # the twin shown in Fig. 1.4(c): the tilted shaft, else the one regulated the most
    shown = tilted[0] if tilted else int(np.argmax([abs(ra.dz2) for ra, _ in reg.members]))
    plot_twin_contact_paths(reg, out / "fig14c_contact_paths.png", shown)
    files = ["summary.json", "te.csv", "fig14_te.png", "fig14c_contact_paths.png"]
    if tilted:
        plot_members(reg, tilted[0], out / "fig15_members.png")
        files.append("fig15_members.png")
    return summarize(reg, files)


def _member_diff(reg: TrainRegulation, which: str, i: int) -> dict:
    a, b = (getattr(r, which) for r in reg.members[i])
    d = (a.te3 - b.te3) / ARCSEC
    return {"max_abs_diff_arcsec": float(np.abs(d).max()),
            "peak_a_arcsec": periodic_peak(a.te3) / ARCSEC, "peak_b_arcsec": periodic_peak(b.te3) / ARCSEC,
            "peak_diff_arcsec": (periodic_peak(a.te3) - periodic_peak(b.te3)) / ARCSEC}


def summarize(reg: TrainRegulation, files: list[str]) -> dict:
    """Summary (JSON-ready): regulation per planet, spreads, integrated TE before/after."""
    tr = reg.train
    rows = []
    for i, ((ra, rb), e) in enumerate(zip(reg.members, reg.errors)):
        rows.append({
            "planet": i + 1,
            "dEx_um": e.d_ex * 1e3,
            "dgamma_arcmin": e.d_gamma / ARCMIN,
            "dz1_mm": ra.dz1, "dz2_mm": ra.dz2, "dz1_b_mm": rb.dz1, "dz2_b_mm": rb.dz2,
            "member_dEx_um": [member_d_ex(tr, "a", e) * 1e3, member_d_ex(tr, "b", e) * 1e3],
            "mirrored": rb is ra,
            "peak_before_arcsec": reg.before.twins[i].peak / ARCSEC,
            "peak_first_order_arcsec": reg.first_order.twins[i].peak / ARCSEC,
            "peak_after_arcsec": reg.after.twins[i].peak / ARCSEC,
            "tca_iterations": ra.iterations + (0 if rb is ra else rb.iterations),
            "edge_contact_after": bool(ra.after.edge_contact or rb.after.edge_contact),
        })
    s = {
        "planets": tr.planets,
        "teeth": [tr.sun.teeth, tr.planet.teeth, tr.ring.teeth],
        "eq_1_3_a": tr.a,
        "carrier_ratio": tr.carrier_ratio,
        "inverted_ratio": tr.inverted_ratio,
        "center_distance_mm": tr.center_distance,
        "regulation": rows,
        "target_peak_arcsec": reg.target / ARCSEC,
        "te_spread_before_arcsec": reg.before.spread / ARCSEC,
        "te_spread_first_order_arcsec": reg.first_order.spread / ARCSEC,
        "te_spread_after_arcsec": reg.after.spread / ARCSEC,
        "spread_reduction": reg.before.spread / max(reg.after.spread, 1e-300),
        "single_planet_in_mesh_before": len(reg.before.summary()["planets_in_mesh"]) == 1,
        "before": reg.before.summary(),
        "first_order": reg.first_order.summary(),
        "after": reg.after.summary(),
        "tca_member_runs": reg.tca_runs,
        "regulation_wall_s": reg.elapsed,
        "regulation_cpu_s": reg.cpu,
        "files": files,
    }
    tilted = [i for i, e in enumerate(reg.errors) if e.d_gamma != 0.0]
    if tilted:
        i = tilted[0]
        s["members_planet"] = i + 1
        s["members_before"] = _member_diff(reg, "before", i)
        s["members_after"] = _member_diff(reg, "after", i)
    return s


def write_te_csv(reg: TrainRegulation, path: Path) -> None:
    """Per φ1: Δφ3 of every planet before and after regulation, integrated TE, planet in mesh."""
    n = reg.train.planets
    cols = ["phi1_deg"] + [f"te_before_{i + 1}_arcsec" for i in range(n)] + [f"te_after_{i + 1}_arcsec" for i in range(n)]
    cols += ["integrated_before_arcsec", "in_mesh_before", "integrated_after_arcsec", "in_mesh_after"]
    b, a = reg.before, reg.after
    tb, ta = b.te / ARCSEC, a.te / ARCSEC
    ib, ia, mb, ma = b.integrated / ARCSEC, a.integrated / ARCSEC, b.in_mesh + 1, a.in_mesh + 1
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(cols)
        for j, p in enumerate(b.phi1):
            w.writerow([f"{math.degrees(p):.9f}", *(f"{v:.6f}" for v in tb[:, j]), *(f"{v:.6f}" for v in ta[:, j]),
                        f"{ib[j]:.6f}", int(mb[j]), f"{ia[j]:.6f}", int(ma[j])])
