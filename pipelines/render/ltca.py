"""Plots of a loaded TCA over a mesh cycle (:mod:`pipelines.models.ltca.run`): loaded and unloaded TE, load
share of the pairs of teeth, Hertz pressure along the contact lines and mesh stiffness, one curve or
panel per torque."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pipelines.render.plots import plt, savefig

__all__ = ["plot_ltca"]


def plot_ltca(rows: list, prows: list, out: Path) -> list[str]:
    """``te_loaded.png``, ``load_share.png``, ``pressure.png`` and ``mesh_stiffness.png`` in ``out`` from the rows of
    ``results.csv`` and ``pressure.csv`` (:func:`pipelines.models.ltca.run.solve_positions`); their file names."""
    torques = sorted({r["torque_nm"] for r in rows})
    files = []
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for q, T in enumerate(torques):
        rs = [r for r in rows if r["torque_nm"] == T]
        x = [r["phi1_deg"] for r in rs]
        if q == 0:
            ax.plot(x, [r["te_unloaded_arcsec"] for r in rs], "k--", label="unloaded (TCA)")
        ax.plot(x, [r["te_loaded_arcsec"] for r in rs], "-", color=f"C{q % 10}", label=f"loaded, T = {T:g} N m")
    ax.set_xlabel(r"$\phi_1$ [deg]")
    ax.set_ylabel("transmission error [arcsec]")
    ax.set_title("Loaded TCA: transmission error over a mesh cycle (negative: the driven gear lags)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    savefig(fig, out / "te_loaded.png")
    files.append("te_loaded.png")
    fig, axs = plt.subplots(len(torques), 1, figsize=(8, 3.0 * len(torques)), squeeze=False, sharex=True)
    for a, T in zip(axs[:, 0], torques):
        rs = [r for r in rows if r["torque_nm"] == T]
        x = np.array([r["phi1_deg"] for r in rs])
        cols = sorted({k for r in rs for k in r if k.startswith("share.")})
        for c in cols:
            a.plot(x, [r.get(c, np.nan) for r in rs], marker=".", ms=3, label=c[6:])
        a.set_ylim(-0.05, 1.05)
        a.set_ylabel("load share")
        a.set_title(f"T = {T:g} N m", fontsize=9)
        a.grid(alpha=0.3)
        a.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.0, 0.5))
    axs[-1, 0].set_xlabel(r"$\phi_1$ [deg]")
    fig.suptitle("Load shared by the pairs of teeth (loaded TCA)")
    savefig(fig, out / "load_share.png")
    files.append("load_share.png")
    fig, axs = plt.subplots(len(torques), 1, figsize=(8, 3.2 * len(torques)), squeeze=False, sharex=True)
    for a, T in zip(axs[:, 0], torques):
        ps = [p for p in prows if p["torque_nm"] == T]
        if ps:
            sc = a.scatter([p["phi1_deg"] for p in ps], [p["z_mm"] for p in ps], c=[p["pressure_mpa"] for p in ps],
                           s=6, cmap="inferno")
            fig.colorbar(sc, ax=a, label="Hertz pressure [MPa]")
        a.set_ylabel("z of the slice [mm]")
        a.set_title(f"T = {T:g} N m", fontsize=9)
    axs[-1, 0].set_xlabel(r"$\phi_1$ [deg]")
    fig.suptitle("Contact pressure along the contact lines through the cycle")
    savefig(fig, out / "pressure.png")
    files.append("pressure.png")
    fig, ax = plt.subplots(figsize=(8, 4))
    for q, T in enumerate(torques):
        rs = [r for r in rows if r["torque_nm"] == T]
        ax.plot([r["phi1_deg"] for r in rs], [r["mesh_stiffness_n_per_um"] for r in rs], color=f"C{q % 10}",
                label=f"T = {T:g} N m")
    ax.set_xlabel(r"$\phi_1$ [deg]")
    ax.set_ylabel("mesh stiffness [N/um]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    savefig(fig, out / "mesh_stiffness.png")
    files.append("mesh_stiffness.png")
    return files
