"""Pictures of flagged peaks: a field on one flank or fillet, unrolled onto (axial position, radius), the peak marked.

An edge or corner contact peak is drawn on the slave flank it was recovered on (contact pressure), a
contact-induced fillet peak on its fillet and the flank above it (largest principal stress); the peak is circled and
labelled with its value, so the picture says where the number of the report comes from.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402
import numpy as np  # noqa: E402

from pipelines.render.plots import savefig  # noqa: E402

__all__ = ["plot_peak_map"]


def plot_peak_map(z: np.ndarray, r: np.ndarray, values: np.ndarray, peak: tuple[float, float], path: Path, title: str,
                  label: str) -> Path:
    """Nodal ``values`` at axial positions ``z`` and radii ``r`` [mm] (one surface), the ``peak`` (z, r) marked."""
    z, r, v = (np.asarray(a, float) for a in (z, r, values))
    fig, ax = plt.subplots(figsize=(8.0, 4.6))
    try:
        tri = mtri.Triangulation(z, r)
        cs = ax.tricontourf(tri, np.nan_to_num(v), levels=24, cmap="jet")
        cb = fig.colorbar(cs, ax=ax)
        cb.set_label(label, fontsize=12)
        cb.ax.tick_params(labelsize=11)
    except (ValueError, RuntimeError):  # degenerate (collinear) node sets: the nodes alone
        sc = ax.scatter(z, r, c=v, cmap="jet", s=12)
        fig.colorbar(sc, ax=ax).set_label(label, fontsize=12)
    ax.plot(z, r, ",", color="k", alpha=0.3)
    ax.plot([peak[0]], [peak[1]], "o", ms=16, mfc="none", mec="magenta", mew=2.5)
    ax.annotate("peak", peak, xytext=(12, 12), textcoords="offset points", color="magenta", fontsize=12, weight="bold")
    ax.set_xlabel("axial position in the gear's frame [mm]", fontsize=12)
    ax.set_ylabel("radius [mm]", fontsize=12)
    ax.tick_params(labelsize=11)
    ax.set_title(title, fontsize=11, wrap=True)
    fig.tight_layout()
    return savefig(fig, path)
