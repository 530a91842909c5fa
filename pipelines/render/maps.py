r"""Engineering plots of FE fields (matplotlib, Agg): flank pressure maps, sections and root stress.

All functions take plain arrays (coordinates in mm, stresses in MPa; a nodal field on a planar
triangulation as a :class:`TriField`) and write one PNG; what the arrays mean is decided by the
caller (:mod:`pipelines.report.figures`).

* :func:`plot_flank_pressure` — nodal contact pressure on a flank in its own coordinates (axial
  position z, radius ρ), Gouraud-shaded over the flank's quadrilaterals split into triangles, the
  FE contact patch outlined (p > :data:`PATCH_FRACTION` × peak), with the TCA path of contact, the
  TCA ellipse and the Hertz ellipse drawn on it.
* :func:`plot_section` — a field on a planar section (in-plane coordinates), the whole section and
  a zoom around a point (the contact), with a depth marked below it.
* :func:`plot_root_stress` — stress along fillets over the face width, one curve per fillet.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from pipelines.render.plots import plt, savefig

__all__ = ["PATCH_FRACTION", "Curve", "TriField", "DepthMark", "plot_flank_pressure", "plot_section", "plot_root_stress",
           "quads_to_triangles"]

PATCH_FRACTION = 0.01  # the FE contact patch: nodal pressure above this fraction of the flank's peak
DPI = 100  # the maps are large figures: 100 dpi keeps them sharp at a third fewer pixels than the plots


@dataclass(frozen=True)
class Curve:
    """A labelled 2D polyline [mm] (a path of contact, an ellipse, a stress curve)."""

    x: np.ndarray
    y: np.ndarray
    label: str
    style: str = "-"
    color: str = "k"


@dataclass(frozen=True, eq=False)
class TriField:
    """A nodal field on a planar triangulation: coordinates ``xy`` (n, 2) [mm], ``triangles`` (m, 3) node
    indices, ``values`` (n,)."""

    xy: np.ndarray
    triangles: np.ndarray
    values: np.ndarray


@dataclass(frozen=True)
class DepthMark:
    """A point marked ``depth`` [mm] below a section's contact point along the unit 2D vector ``down`` (into
    the surface)."""

    depth: float
    down: tuple


def quads_to_triangles(quads: np.ndarray) -> np.ndarray:
    """(n, 4) quadrilaterals -> (2n, 3) triangles (diagonal 0-2)."""
    q = np.asarray(quads)
    return np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])


def plot_flank_pressure(flank: TriField, path: Path, *, curves=(), point=None, area=None, title: str = "",
                        zoom: float | None = None) -> Path:
    """Contact pressure [MPa] on a flank over (z, radius) [mm] with TCA curves (module docstring).

    `area`: (z_min, z_max, r_lo, r_hi) working area drawn as a rectangle; `point`: (z, r) of the TCA
    contact point; `zoom` [mm]: half-width of a second panel centred on the point (None: one panel).
    """
    import matplotlib.tri as mtri

    zr = np.asarray(flank.xy, float)
    p = np.nan_to_num(np.asarray(flank.values, float))
    tri = mtri.Triangulation(zr[:, 0], zr[:, 1], np.asarray(flank.triangles))
    peak = float(p.max(initial=0.0))
    panels = 2 if zoom and point is not None else 1
    fig, axs = plt.subplots(1, panels, figsize=(6.2 * panels, 5.6), squeeze=False)
    fig.subplots_adjust(left=0.065 * 2 / panels, right=0.9, bottom=0.2, top=0.9, wspace=0.2)
    for k, ax in enumerate(axs[0]):
        ax.set_facecolor("0.85")
        pc = ax.tripcolor(tri, p, shading="gouraud", cmap="jet", vmin=0.0, vmax=peak or 1.0)
        if peak > 0:
            ax.tricontour(tri, p, levels=[PATCH_FRACTION * peak], colors="white", linewidths=1.2)
        if area is not None:
            z0, z1, r0, r1 = area
            ax.add_patch(plt.Rectangle((z0, min(r0, r1)), z1 - z0, abs(r1 - r0), fill=False, ec="0.3", lw=1, ls=":"))
        for c in curves:
            ax.plot(c.x, c.y, c.style, color=c.color, lw=1.4, ms=3, label=c.label if k == 0 else None)
        if point is not None:
            ax.plot([point[0]], [point[1]], "+", color="k", ms=12, mew=2, label="TCA contact point" if k == 0 else None)
        ax.set_xlabel("z [mm] (face width)")
        ax.set_ylabel("radius [mm]")
        if k == 1:
            ax.set_xlim(max(point[0] - zoom, zr[:, 0].min() - 0.5), min(point[0] + zoom, zr[:, 0].max() + 0.5))
            ax.set_ylim(max(point[1] - 0.75 * zoom, zr[:, 1].min() - 0.3), min(point[1] + 0.75 * zoom, zr[:, 1].max() + 0.3))
            ax.set_title(f"around the TCA contact point (±{zoom:.2g} mm)", fontsize=9)
        else:
            ax.set_xlim(zr[:, 0].min() - 1, zr[:, 0].max() + 1)
            ax.set_ylim(zr[:, 1].min() - 0.5, zr[:, 1].max() + 0.5)
            ax.set_title("loaded flank (working area dotted; not to scale)", fontsize=9)
    fig.colorbar(pc, cax=fig.add_axes([0.915, 0.2, 0.015, 0.7]), label="FE contact pressure [MPa]")
    axs[0, 0].plot([], [], color="white", lw=3, label=f"FE patch (p > {PATCH_FRACTION:g} x peak)")
    leg = fig.legend(loc="lower center", ncol=3, fontsize=8, frameon=True)
    leg.get_frame().set_facecolor("0.8")
    fig.suptitle(title or f"Contact pressure, peak {peak:.0f} MPa", fontsize=10)
    return savefig(fig, path, dpi=DPI)  # tight: the colour bars' labels inside the picture


def plot_section(section: TriField, path: Path, *, vmax: float, point=None, depth: DepthMark | None = None,
                 zoom: float | None = None, title: str = "", label: str = "von Mises [MPa]") -> Path:
    """A field on a planar section over its in-plane coordinates [mm] (module docstring).

    Left: the whole section on 0…`vmax` (values above in magenta, the colour bar says so); right
    (when `zoom` [mm] and `point` are given): a square of half-width `zoom` around `point` on the
    full range of the values shown there. `depth` marks a point below `point` (the depth of the
    Hertz maximum shear stress).
    """
    import matplotlib.tri as mtri

    xy = np.asarray(section.xy, float)
    v = np.nan_to_num(np.asarray(section.values, float))
    tri = mtri.Triangulation(xy[:, 0], xy[:, 1], np.asarray(section.triangles))
    panels = 2 if zoom and point is not None else 1
    fig, axs = plt.subplots(1, panels, figsize=(6.6 * panels, 5.8), squeeze=False)
    fig.subplots_adjust(left=0.07 * 2 / panels, right=0.97, bottom=0.17, top=0.9, wspace=0.3)
    cmap = plt.get_cmap("jet").with_extremes(over="magenta")
    vmax = float(vmax) or 1.0
    for k, ax in enumerate(axs[0]):
        if k == 1:
            near = np.all(np.abs(xy - np.asarray(point)) <= zoom, axis=1)
            top = float(v[near].max(initial=0.0)) or vmax
        else:
            top = vmax
        pc = ax.tripcolor(tri, v, shading="gouraud", cmap=cmap, vmin=0.0, vmax=top)
        clipped = float(v.max(initial=0.0)) > top * (1 + 1e-9) and k == 0
        fig.colorbar(pc, ax=ax, extend="max" if clipped else "neither", shrink=0.8, fraction=0.05, pad=0.03,
                     label=label + (f", clipped at {top:.0f} (max {v.max():.0f})" if clipped else ""))
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm] (in the section)")
        ax.set_ylabel("y [mm] (radial, slave gear)")
        if point is not None:
            ax.plot([point[0]], [point[1]], "+", color="k", ms=12, mew=2, label="TCA contact point" if k == 0 else None)
            if depth is not None:
                q = np.asarray(point) + depth.depth * np.asarray(depth.down)
                ax.plot([q[0]], [q[1]], "x", color="w", ms=8, mew=2,
                        label=f"Hertz max. shear depth 0.78 b = {depth.depth * 1e3:.0f} µm" if k == 0 else None)
        if k == 1:
            ax.set_xlim(point[0] - zoom, point[0] + zoom)
            ax.set_ylim(point[1] - zoom, point[1] + zoom)
            ax.set_title(f"under the contact (±{zoom:.2g} mm), full range", fontsize=9)
        else:
            ax.set_title("both loaded teeth and their fillets", fontsize=9)
    if point is not None:
        fig.legend(loc="lower center", ncol=2, fontsize=8, frameon=True).get_frame().set_facecolor("0.8")
    fig.suptitle(title, fontsize=10)
    return savefig(fig, path, dpi=DPI)  # tight: the colour bars' labels inside the picture


def plot_root_stress(panels: list, path: Path, title: str = "", xlabel: str = "axial position [mm]") -> Path:
    """Stress along fillets: `panels` is a list of (panel title, [Curve(z [mm], stress [MPa], label)])."""
    n = max(1, len(panels))
    fig, axs = plt.subplots(n, 1, figsize=(10, 3.4 * n), squeeze=False)
    fig.subplots_adjust(left=0.08, right=0.62, bottom=0.16 / n, top=1 - 0.2 / n, hspace=0.5)
    for ax, (name, curves) in zip(axs[:, 0], panels):
        for c in curves:
            ax.plot(c.x, c.y, c.style, color=c.color, lw=1.6, marker=".", ms=4, label=c.label)
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.set_title(name, fontsize=9)
        ax.set_xlabel(xlabel)
        ax.set_ylabel("max. principal stress [MPa]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.0, 0.5))
    fig.suptitle(title or "Root stress along the fillets of the loaded teeth", fontsize=10)
    return savefig(fig, path, dpi=DPI)  # tight: the colour bars' labels inside the picture
