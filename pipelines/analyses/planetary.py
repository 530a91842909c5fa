"""TCA of the double-helical planetary train (kind = "planetary"): regulation and integrated TE (Part 1).

Case keys: ``planets`` (n), ``member_gap_mm`` (F), gears ``[gears.sun]``, ``[gears.planet]``,
``[gears.ring]`` (members *a*; members *b* are their mirror images), ``[installment]`` with lists of
n values ``d_ex_um`` (ΔE_x, positive against the sun's rotation) and ``d_gamma_arcmin`` (Δγ about
the radial line through the shaft centre), ``[regulation]`` ``tol_arcsec``, ``max_iterations``,
and ``[tca]`` (``steps_per_cycle`` a multiple of n). Writes ``summary.json`` (``regulation`` per
planet, spreads), ``te.csv``, ``fig14_te.png`` (Fig. 1.4(a)/(b)), ``fig14c_contact_paths.png``
and, when a shaft has Δγ, ``fig15_members.png`` (Fig. 1.5).
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from tca.pair.analysis import ARCSEC, ContactKind
from tca.planetary.regulation import (RegulationOptions, TrainRegulation, TrainTE, member_d_ex, periodic_peak,
                                     regulate_train)

from pipelines.cases.planetary import read_installment, read_regulation_options, read_train
from pipelines.cases.reader import ARCMIN, read_tca_options
from pipelines.render.plots import savefig
from pipelines.cases.schema import Table

import matplotlib.pyplot as plt  # noqa: E402  (backend set by .plots)

__all__ = ["run", "plot_train_te", "plot_members", "plot_twin_contact_paths"]



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


# ------------------------------------------------------------------------------------------ plots
def _te_panel(ax, t: TrainTE, j_star: int, label: str):
    x = np.degrees(t.phi1)
    te = t.te / ARCSEC
    lead = int(t.in_mesh[j_star])
    for i, row in enumerate(te):
        bl = t.backlash[i, j_star] / ARCSEC
        lab = f"$2^{{({i + 1})}}$" + ("  in mesh" if i == lead else f"  $|M_{{{lead + 1}}}M_{{{i + 1}}}|$ = {bl:.1f}\"")
        ax.plot(x, row, lw=1.3, color=f"C{i}", label=lab)
        ax.plot(x[j_star], row[j_star], "o", color=f"C{i}", ms=5)
        ax.annotate(f"$M_{i + 1}$", (x[j_star], row[j_star]), textcoords="offset points", xytext=(4, 3), fontsize=7)
    ax.plot(x, t.integrated / ARCSEC, color="k", lw=2.2, ls="--", alpha=0.6, label="integrated (planet in mesh)")
    ax.axvline(x[j_star], color="0.6", lw=0.8, ls=":")
    ax.set_xlabel(r"$\phi_1$ [deg]")
    ax.set_ylabel(r"$\Delta\phi_3^{(i)}$ [arcsec]")
    ax.set_title(f"{label}: spread of maxima {t.spread / ARCSEC:.3g}\"")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")


def plot_train_te(reg: TrainRegulation, path: Path, title: str = "") -> Path:
    """Fig. 1.4(a)/(b): Δφ3^(i)(φ1) of all planets before and after regulation, points M_i at φ1*."""
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.8))
    j_star = len(reg.before.phi1) // 3
    _te_panel(axes[0], reg.before, j_star, "(a) before regulation")
    _te_panel(axes[1], reg.after, j_star, r"(b) after regulation ($\Delta Z^{(2)}$)")
    fig.suptitle(title or "Transmission errors of the planetary train (carrier at rest)")
    return savefig(fig, path)


def plot_members(reg: TrainRegulation, i: int, path: Path) -> Path:
    """Fig. 1.5: Δφ3a and Δφ3b of the members of shaft i before and after their axial regulation."""
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.4), sharey=False)
    ra, rb = reg.members[i]
    for ax, which, lab in ((axes[0], "before", "(a) before regulation"), (axes[1], "after", "(b) after regulation")):
        a, b = getattr(ra, which), getattr(rb, which)
        x = np.degrees(a.phi1)
        ax.plot(x, a.te3_arcsec, color="C0", lw=1.5, label=rf"$\Delta\phi_{{3a}}^{{({i + 1})}}$, $\Delta Z_a$ = {a.dz:.3f} mm")
        ax.plot(x, b.te3_arcsec, color="C3", lw=1.5, label=rf"$\Delta\phi_{{3b}}^{{({i + 1})}}$, $\Delta Z_b$ = {b.dz:.3f} mm")
        d = np.abs(a.te3_arcsec - b.te3_arcsec).max()
        ax.set_title(f"{lab}: max |a - b| = {d:.3g}\"")
        ax.set_xlabel(r"$\phi_1$ [deg]")
        ax.set_ylabel(r"$\Delta\phi_{3k}$ [arcsec]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    e = reg.errors[i]
    fig.suptitle(f"Members a and b of planet {i + 1}: " + r"$\Delta\gamma$" + f" = {e.d_gamma / ARCMIN:g} arcmin")
    return savefig(fig, path)


def plot_twin_contact_paths(reg: TrainRegulation, path: Path, shaft: int = 0) -> Path:
    """Fig. 1.4(c): paths of contact on the twin planet (members a, b) with the sun and with the ring."""
    tr = reg.train
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.4))
    for ax, mesh, side, lab in ((axes[0], "mesh12", -1, "with the sun (coast flank)"),
                                (axes[1], "mesh23", 1, "with the ring (drive flank)")):
        for k, (r, col) in enumerate(zip(reg.members[shaft], ("C0", "C3"))):
            member = "ab"[k]
            sub = r.after
            res = getattr(sub, mesh).result
            planet = tr.gears(member)[1]
            pts = res.point2 if mesh == "mesh12" else res.point1
            zc = tr.member_sign(member) * tr.member_offset + sub.dz * tr.dz_direction(member)
            zf = zc - pts[:, 2]  # planet frame z = -z_f
            rad = np.hypot(pts[:, 0], pts[:, 1])
            ar = planet.area(side)
            ax.add_patch(plt.Rectangle((zc - ar.z_max, ar.r_form), ar.z_max - ar.z_min, ar.r_tip - ar.r_form,
                                       fill=False, ec="0.4", lw=1))
            edge = (res.kind == ContactKind.EDGE) | (res.kind == ContactKind.CORNER)
            ax.plot(zf, rad, ".", color=col, ms=3, label=f"member {member} (" + r"$\Delta Z$" + f" = {sub.dz:.3f} mm)")
            if edge.any():
                ax.plot(zf[edge], rad[edge], "o", mfc="none", color="k", ms=5)
        ax.set_title(f"planet {shaft + 1}, {lab}; o = edge contact")
        ax.set_xlabel(r"axial position along the shaft $z_f$ [mm]")
        ax.set_ylabel("radius [mm]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Paths of contact of a twin subgear drive (after regulation)")
    return savefig(fig, path)
