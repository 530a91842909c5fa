"""Figures of the isostatic planetary train (Part 3 of the report, :mod:`pipelines.analyses.isostatic`): the
trajectory of the sun centre with its best-fit circle and the carrier transmission errors, Eq. (3.23)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from tca.isostatic.result import IsostaticResult

from pipelines.render.plots import plt, savefig

__all__ = ["plot_sun_center", "plot_carrier_te"]


def plot_sun_center(r: IsostaticResult, path: Path, title: str | None = None) -> Path:
    """Trajectory of the sun centre [um] with its best-fit circle (Figs. 3.5(a)-3.15(a))."""
    fig, ax = plt.subplots(figsize=(5.6, 5.2))
    p = r.sun_center_um
    ax.plot(p[:, 0], p[:, 1], "-", color="C0", lw=1)
    ax.plot(p[0, 0], p[0, 1], "o", color="C3", ms=4, label="start")
    c, rad = r.sun_circle
    if rad > 0:
        t = np.linspace(0, 2 * math.pi, 200)
        ax.plot(c[0] + rad * np.cos(t), c[1] + rad * np.sin(t), ":", color="0.5", lw=0.8,
                label=f"best-fit circle, R = {rad:.3f} um")
    ax.plot(0, 0, "+", color="k", ms=8)
    span = max(float(np.abs(p).max()), 0.05)
    ax.set_xlim(-1.15 * span, 1.15 * span)
    ax.set_ylim(-1.15 * span, 1.15 * span)
    ax.set_aspect("equal")
    ax.set_xlabel(r"$\Delta E_{1x}$ [um]")
    ax.set_ylabel(r"$\Delta E_{1y}$ [um]")
    ax.set_title(title or "Trajectory of the sun centre")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    return savefig(fig, path)


def plot_carrier_te(r: IsostaticResult, path: Path, title: str | None = None) -> Path:
    """Carrier transmission errors, Eq. (3.23), over the run (Figs. 3.5(b)-3.15(b))."""
    fig, ax = plt.subplots(figsize=(8, 4))
    rel = (r.phi_c - r.phi_c[0])
    if rel[-1] >= 0.99 * 2 * math.pi:  # one or more carrier turns: abscissa in carrier angle
        x, xl = np.degrees(rel), r"carrier rotation $\phi_c - \phi_c^{(0)}$ [deg]"
    else:
        x, xl = (r.phi1 - r.phi1[0]) / (2 * math.pi), "sun revolutions"
    te = r.te_arcsec
    ax.plot(x, te, color="C0", lw=1.2)
    span = float(np.ptp(te))
    m = float(te.mean())
    half = max(0.6 * span, 1.0)
    ax.set_ylim(min(m - half, te.min() - 0.1 * half), max(m + half, te.max() + 0.1 * half))
    ax.axhline(0, color="0.5", lw=0.6)
    ax.set_xlabel(xl)
    ax.set_ylabel(r"$\Delta\phi_c$ [arcsec]")
    ax.set_title(title or "Transmission errors of the carrier")
    ax.text(0.01, 0.02, f"mean {m:.3f} arcsec, peak-to-peak {span:.3f} arcsec", transform=ax.transAxes, fontsize=8)
    ax.grid(alpha=0.3)
    return savefig(fig, path)
