"""Plots and page of a stress sweep through the mesh cycle (:mod:`pipelines.sweep.points`, ``gearfe sweep``).

From the rows of the sweep's ``results.csv`` (one per grid point; one curve per group of the axes
other than the position): loaded and unloaded TE, load share of the modelled tooth pairs, peak
contact pressure and root stress against the driver angle, and ``report.html`` with the plots and
the table of points. Files are written under a temporary name and renamed into place
(:func:`pipelines.render.plots.savefig`): a killed sweep leaves no half file.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

__all__ = ["plot_cycle", "CYCLE_STRESSES", "plot_stresses", "REPORT_COLUMNS", "write_cycle_report"]


def _num(x) -> float:
    try:
        return float(x)
    except (TypeError, ValueError):
        return float("nan")


def plot_cycle(rows: list[dict], keys: list[str], position_key: str, out: Path) -> list[Path]:
    """From the rows of a sweep over positions (one curve per group of the other axes), in ``out``:
    te_loaded.png, load_share.png, stress_cycle.png (peak contact pressure and root stress) and
    report.html (the three plots and the table of points, self-contained)."""
    from pipelines.render.plots import plt, savefig

    ok = [r for r in rows if r.get("status") == "ok"]
    if len({_num(r["phi1_deg"]) for r in ok}) < 2:
        return []
    others = [k for k in keys if k != position_key]
    groups: dict = {}
    for r in ok:
        groups.setdefault(tuple(str(r[k]) for k in others), []).append(r)
    label = {g: ", ".join(f"{k} = {v}" for k, v in zip(others, g)) or "sweep" for g in groups}
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for q, (g, rs) in enumerate(groups.items()):
        rs = sorted(rs, key=lambda r: _num(r["phi1_deg"]))
        x = [_num(r["phi1_deg"]) for r in rs]
        ax.plot(x, [_num(r["te_unloaded_arcsec"]) for r in rs], "--", color=f"C{q % 10}", marker=".",
                label=f"unloaded (TCA), {label[g]}")
        ax.plot(x, [_num(r["te_loaded_arcsec"]) for r in rs], "-", color=f"C{q % 10}", marker="o", ms=4,
                label=f"loaded (TCA + FE), {label[g]}")
    ax.set_xlabel(r"$\phi_1$ [deg]")
    ax.set_ylabel("transmission error [arcsec]")
    ax.set_title("Loaded and unloaded transmission error (negative: the driven gear lags)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    paths = [savefig(fig, out / "te_loaded.png")]
    ng = len(groups)
    fig, axs = plt.subplots(ng, 1, figsize=(8, 3.2 * ng), squeeze=False, sharex=True)
    for a, (g, rs) in zip(axs[:, 0], groups.items()):
        rs = sorted(rs, key=lambda r: _num(r["phi1_deg"]))
        x = np.array([_num(r["phi1_deg"]) for r in rs])
        cols = sorted({k for r in rs for k in r if k.startswith("share.") and ".teeth." in k and r[k] not in ("", None)})
        for c in cols:
            y = np.array([_num(r.get(c)) for r in rs])
            a.plot(x, y, marker="o", ms=3.5, label=c.split(".teeth.", 1)[1] + f" ({c.split('.')[1]})")
        a.set_ylim(-0.05, 1.05)
        a.set_ylabel("load share")
        a.set_title(label[g], fontsize=9)
        a.grid(alpha=0.3)
        a.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.0, 0.5))
    axs[-1, 0].set_xlabel(r"$\phi_1$ [deg]")
    fig.suptitle("Load shared by neighbouring tooth pairs through the mesh cycle (FE normal forces)")
    paths.append(savefig(fig, out / "load_share.png"))
    paths.append(plot_stresses(groups, label, out / "stress_cycle.png"))
    paths.append(write_cycle_report(ok, rows, keys, out, paths))
    return paths


CYCLE_STRESSES = (("max_contact_pressure_mpa", "peak contact pressure [MPa]"),
                  ("max_fillet_stress_mpa", "root stress: largest principal\nstress on the fillets [MPa]"))


def plot_stresses(groups: dict, label: dict, path: Path) -> Path:
    """stress_cycle.png: peak contact pressure and root stress (largest fillet principal stress) vs φ1, per group."""
    from pipelines.render.plots import plt, savefig

    fig, axs = plt.subplots(len(CYCLE_STRESSES), 1, figsize=(8, 3.3 * len(CYCLE_STRESSES)), sharex=True, squeeze=False)
    for ax, (key, name) in zip(axs[:, 0], CYCLE_STRESSES):
        for q, (g, rs) in enumerate(groups.items()):
            rs = sorted(rs, key=lambda r: _num(r["phi1_deg"]))
            ax.plot([_num(r["phi1_deg"]) for r in rs], [_num(r.get(key)) for r in rs], "-", marker="o", ms=4,
                    color=f"C{q % 10}", label=label[g])
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="best")
    axs[-1, 0].set_xlabel(r"$\phi_1$ [deg]")
    fig.suptitle("Peak contact pressure and root stress through the mesh cycle (FE)")
    return savefig(fig, path)


REPORT_COLUMNS = ("id", "phi1_deg", "torque_nm", "te_unloaded_arcsec", "te_loaded_arcsec", "max_contact_pressure_mpa",
                  "max_fillet_stress_mpa", "max_von_mises_mpa", "contact_force_n", "torque_balance_error", "dofs", "status")


def write_cycle_report(ok: list[dict], rows: list[dict], keys: list[str], out: Path, plots: list[Path]) -> Path:
    """``report.html`` of a stress sweep: the plots through the cycle and one table row per point (self-contained)."""
    from pipelines.render.html import image, section, table, write_page

    cols = [c for c in ("id", *keys) if c not in REPORT_COLUMNS] + list(REPORT_COLUMNS)
    caps = {"te_loaded.png": "Loaded (TCA + FE elastic rotation) and unloaded (TCA) transmission error",
            "load_share.png": "Load share of the modelled tooth pairs (FE normal forces)",
            "stress_cycle.png": "Peak contact pressure and root stress through the mesh cycle"}
    blocks = [f"<p>{len(ok)} of {len(rows)} points solved; axes: {', '.join(keys)}.</p>",
              section("Through the mesh cycle", *(image(p, caps.get(Path(p).name, "")) for p in plots)),
              section("Points", table(rows, [c for c in cols if any(c in r for r in rows)]))]
    tmp = out / ".report.tmp.html"
    write_page(tmp, "Stress sweep through the mesh cycle", *blocks)
    os.replace(tmp, out / "report.html")
    return out / "report.html"
