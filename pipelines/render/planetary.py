"""Figures of the double-helical planetary train (Part 1 of the report, :mod:`pipelines.analyses.planetary`):
the planets' TE before and after regulation (Fig. 1.4(a)/(b)), the members of a shaft (Fig. 1.5) and the
paths of contact on a twin planet (Fig. 1.4(c)). TE in arcsec."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from tca.pair.result import ContactKind
from tca.planetary.regulation import TrainRegulation, TrainTE
from tca.units import ARCMIN, ARCSEC

from pipelines.render.plots import plt, savefig

__all__ = ["plot_train_te", "plot_members", "plot_twin_contact_paths"]


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
