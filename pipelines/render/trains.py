"""Plots of the loaded TCA of a planetary train (:mod:`pipelines.models.trains.ltca`): planet shares against the
carrier angle, the loaded TE of the train, the sun centre's loaded path, one curve per planet or torque."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from pipelines.render.plots import plt, savefig

__all__ = ["plot_train_ltca", "plot_compare_trains"]


def plot_train_ltca(runs: list, out: Path, title: str = "") -> list[str]:
    """``planet_shares.png``, ``te_train.png`` and (where the sun moves) ``sun_center.png`` in ``out`` from the
    :class:`pipelines.models.trains.run.TrainRun` of each torque; their file names."""
    files = []
    n = runs[0].planets
    fig, axs = plt.subplots(len(runs), 1, figsize=(8, 3.2 * len(runs)), squeeze=False, sharex=True)
    for a, r in zip(axs[:, 0], runs):
        x = np.degrees(r.carrier)
        for i in range(n):
            a.plot(x, r.sun_share[:, i], "-", color=f"C{i % 10}", lw=1.0, label=f"planet {i + 1}, sun mesh")
            a.plot(x, r.ring_share[:, i], ":", color=f"C{i % 10}", lw=1.0, label=f"planet {i + 1}, ring mesh")
        a.axhline(1.0 / n, color="k", lw=0.6, ls="--")
        a.set_ylabel("share of the torque")
        a.set_title(f"T = {r.torque * 1e-3:g} N m on the sun: K_gamma = {r.k_gamma:.4f}", fontsize=9)
        a.grid(alpha=0.3)
        a.legend(fontsize=6, loc="center left", bbox_to_anchor=(1.0, 0.5))
    axs[-1, 0].set_xlabel("carrier angle [deg]")
    fig.suptitle(f"Planet load shares (loaded TCA of the train){': ' + title if title else ''}", fontsize=10)
    savefig(fig, out / "planet_shares.png")
    files.append("planet_shares.png")
    fig, ax = plt.subplots(figsize=(8, 4.0))
    for q, r in enumerate(runs):
        ax.plot(np.degrees(r.carrier), r.te / (math.pi / 180 / 3600), "-", color=f"C{q % 10}",
                label=f"T = {r.torque * 1e-3:g} N m")
    ax.set_xlabel("carrier angle [deg]")
    ax.set_ylabel("carrier angle error [arcsec]")
    ax.set_title("Loaded TE of the train: carrier angle minus its kinematic angle (negative: lags)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    savefig(fig, out / "te_train.png")
    files.append("te_train.png")
    if any(np.abs(r.sun_center).max() > 0 for r in runs):
        fig, ax = plt.subplots(figsize=(5.5, 5.5))
        for q, r in enumerate(runs):
            c = r.sun_center * 1e3
            ax.plot(c[:, 0], c[:, 1], "-", color=f"C{q % 10}", lw=1.0, label=f"T = {r.torque * 1e-3:g} N m")
            ax.plot(c[:1, 0], c[:1, 1], "o", color=f"C{q % 10}", ms=4)
        ax.plot([0], [0], "k+")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x [um]")
        ax.set_ylabel("y [um]")
        ax.set_title("Sun centre under load (fixed frame; o: start)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
        savefig(fig, out / "sun_center.png")
        files.append("sun_center.png")
    return files


def plot_compare_trains(runs: dict, out: Path) -> str:
    """``compare_shares.png``: the largest planet share (n x max share) of each train against the carrier angle,
    and its K_γ, one curve per train (``runs``: label -> TrainRun of the first torque); the file name."""
    fig, ax = plt.subplots(figsize=(8, 4.0))
    for q, (label, r) in enumerate(runs.items()):
        ax.plot(np.degrees(r.carrier), r.planets * r.sun_share.max(1), "-", color=f"C{q % 10}", lw=1.0,
                label=f"{label}: K_gamma = {r.k_gamma:.4f}")
    ax.axhline(1.0, color="k", lw=0.6, ls="--")
    ax.set_xlabel("carrier angle [deg]")
    ax.set_ylabel("n x largest planet share")
    ax.set_title("Load sharing of two trains (loaded TCA)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    savefig(fig, out / "compare_shares.png")
    return "compare_shares.png"
