"""Figures of the face-gear planetary train (Part 2 of the report, :mod:`pipelines.analyses.face`).

Transmission errors of the sub-drives (Fig. 2.3), the integrated TE (Figs. 2.4, 2.8) for one and
several installation angles (Figs. 2.6, 2.7, 2.9), paths of contact (Fig. 2.5) and the peak-to-peak
TE against the installation angle. TE in arcsec; the integrated TE is drawn with its maximum at zero.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from tca.face.train import FaceTrainResult
from tca.units import ARCSEC

from pipelines.render.plots import plt, savefig

__all__ = ["BRANCH_NAMES", "plot_subdrives", "plot_integrated", "plot_delta_cases", "plot_particular", "plot_scan",
           "plot_contact_paths"]

BRANCH_NAMES = {-1: "forward", 0: "middle", 1: "backward"}  # the pair of sub-drive 2 in contact (pair_b)


def _te_axes(ax, r: FaceTrainResult, te_name: str, name_in: str, label: bool = True):
    x = np.degrees(r.phi_in)
    te = r.te_arcsec - r.te_arcsec.max()  # as the report: the maximum at zero
    for jb, color in ((-1, "C2"), (0, "C0"), (1, "C3")):
        m = r.pair_b == jb
        if m.any():
            y = np.where(m, te, np.nan)
            ax.plot(x, y, color=color, lw=2, label=f"{BRANCH_NAMES[jb]} pair of sub-drive 2" if label else None)
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
