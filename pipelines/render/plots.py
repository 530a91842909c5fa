"""Plots of TCA results (matplotlib, Agg backend): transmission errors and paths of contact; :func:`savefig`,
the one way every plot of :mod:`pipelines.render` is written."""

from __future__ import annotations

import math
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from tca.pair.analysis import ARCSEC, ContactKind, PairTCAResult, ellipse_outlines  # noqa: E402

from pipelines.render.settings import picture_settings  # noqa: E402

__all__ = ["plot_pair_te", "plot_contact_paths", "plot_position_te", "savefig", "side_by_side"]


def savefig(fig, path: Path, dpi: int = 130, tight: bool = True) -> Path:
    """Save and close a figure (plots are made in loops: never leak figures).

    The file is written under a temporary name and renamed into place: a killed run (a sweep) leaves
    no half PNG. ``dpi`` is scaled and the PNG compressed as :func:`pipelines.render.settings.picture_settings`
    says (by default as given, zlib level 6). ``tight=False`` for figures with a constrained layout: a tight
    bounding box draws them twice.
    """
    path = Path(path)
    tmp = path.with_name(f".{path.stem}.tmp{path.suffix}")
    s = picture_settings()
    png = {"pil_kwargs": {"compress_level": s.png_compression}} if path.suffix.lower() == ".png" else {}
    fig.savefig(tmp, dpi=s.dpi(dpi), bbox_inches="tight" if tight else None, **png)
    plt.close(fig)
    os.replace(tmp, path)
    return path


def plot_pair_te(r: PairTCAResult, path: Path, title: str = "") -> Path:
    """TE function over the cycles: the pair in contact (thick), neighbouring pairs (thin), edge contact."""
    fig, ax = plt.subplots(figsize=(8, 4.2))
    ref = r.reference
    pitch = 2 * math.pi / r.pair.gear1.teeth
    te_ref = (ref.phi2 - r.pair.ratio * ref.phi1) / ARCSEC
    lo, hi = r.phi1.min(), r.phi1.max()
    # the neighbouring pairs repeat the reference pair shifted by a pitch, except with run-out
    # (each pair then sees the eccentricity at its own angle: tca.pair.runout), where they are not drawn
    shifts = range(-4, 5) if not (r.pair.gear1.runout or r.pair.gear2.runout) else ()
    for k in shifts:
        x = ref.phi1 + k * pitch
        sel = (x >= lo - 1e-12) & (x <= hi + 1e-12) & np.isfinite(te_ref)
        if sel.any():
            ax.plot(np.degrees(x[sel]), te_ref[sel], color="0.75", lw=0.8, zorder=1)
    ax.plot(np.degrees(r.phi1), r.te_arcsec, color="C0", lw=2, zorder=2, label="pair in contact")
    edge = (r.kind == ContactKind.EDGE) | (r.kind == ContactKind.CORNER)
    if edge.any():
        ax.plot(np.degrees(r.phi1[edge]), r.te_arcsec[edge], "o", ms=3.5, color="C3", zorder=3, label="edge contact")
    for t in r.transitions:
        ax.axvline(math.degrees(t), color="0.5", ls=":", lw=0.8)
    span = r.te_arcsec.max() - r.te_arcsec.min()
    if span < 1e-3:  # a flat TE: show it on a sensible scale instead of round-off noise
        m = r.te_arcsec.mean()
        ax.set_ylim(m - 1, m + 1)
    else:  # the pair in contact, with the neighbouring pairs' branches where they come close
        ax.set_ylim(r.te_arcsec.min() - 0.6 * span, r.te_arcsec.max() + 0.25 * span)
    ax.set_xlabel(r"$\phi_1$ [deg]")
    ax.set_ylabel(r"$\Delta\phi_2$ [arcsec]")
    ax.set_title(title or f"Transmission errors, peak-to-peak {r.te_peak_to_peak_arcsec:.3g} arcsec")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    return savefig(fig, path)


def plot_contact_paths(r: PairTCAResult, path: Path, names=("gear 1", "gear 2")) -> Path:
    """Paths of contact (Eq. 1.14) and contact ellipses on both tooth surfaces, in (z, radius)."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    for which, ax, pts, gear, side in ((1, axes[0], r.point1, r.pair.gear1, r.pair.side1),
                                       (2, axes[1], r.point2, r.pair.gear2, r.pair.side2)):
        ar = gear.area(side)
        # working area: z limits and the radii of the start of the fillet and the tip
        ax.add_patch(plt.Rectangle((ar.z_min, min(ar.r_form, ar.r_tip)), ar.z_max - ar.z_min,
                                   abs(ar.r_tip - ar.r_form), fill=False, ec="0.4", lw=1))
        ell = ellipse_outlines(r, which)
        for e in ell[:: max(1, len(ell) // 12)]:
            if np.all(np.isfinite(e)):
                ax.plot(e[:, 2], np.hypot(e[:, 0], e[:, 1]), color="C1", lw=0.7)
        rad = np.hypot(pts[:, 0], pts[:, 1])
        edge = (r.kind == ContactKind.EDGE) | (r.kind == ContactKind.CORNER)
        ax.plot(pts[:, 2], rad, ".", color="C0", ms=3)
        if edge.any():
            ax.plot(pts[edge, 2], rad[edge], "o", color="C3", ms=4, label="edge contact")
            ax.legend(fontsize=8)
        ax.set_title(f"{names[which - 1]} ({'+y' if side > 0 else '-y'} flank)")
        ax.set_xlabel("z [mm]")
        ax.set_ylabel("radius [mm]")
        ax.grid(alpha=0.3)
    fig.suptitle("Paths of contact and contact ellipses")
    return savefig(fig, path)


def plot_position_te(tca, phi1: float, path: Path, title: str = "") -> Path:
    """TE [arcsec] over the TCA grid with the analysed position φ1 [rad] marked (a PairTCAResult, or a twin drive's
    TwinTE with its members)."""
    fig, ax = plt.subplots(figsize=(8, 4.2))
    if isinstance(tca, PairTCAResult):
        ax.plot(np.degrees(tca.phi1), tca.te_arcsec, color="C0", lw=2, label=r"$\Delta\phi_2$ (pair in contact)")
        at = float(np.interp(phi1, tca.phi1, tca.te_arcsec))
        ylabel = r"$\Delta\phi_2$ [arcsec]"
    else:  # TwinTE
        x = np.degrees(tca.phi1)
        for k, c in (("a", "C0"), ("b", "C2")):
            ax.plot(x, tca.members[k].te3 / ARCSEC, color=c, lw=1.2, ls="--", label=f"member {k}")
        ax.plot(x, tca.te / ARCSEC, color="k", lw=2, label="twin drive, Eq. (1.15)")
        at = float(np.interp(phi1, tca.phi1, tca.te / ARCSEC))
        ylabel = r"$\Delta\phi_3$ [arcsec]"
    ax.plot([math.degrees(phi1)], [at], "o", ms=8, color="C3", zorder=5, label=f"analysed: {math.degrees(phi1):.4f} deg")
    ax.set_xlabel(r"$\phi_1$ [deg]")
    ax.set_ylabel(ylabel)
    ax.set_title(title or "Transmission error and the analysed position")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    return savefig(fig, path)


def side_by_side(images: list[Path], titles: list[str], path: Path, suptitle: str = "", ncols: int | None = None) -> Path:
    """Images placed side by side with titles (as Fig. 1.9 (a) and (b)), in rows of ``ncols``."""
    import matplotlib.image as mpimg

    ncols = ncols or len(images)
    nrows = -(-len(images) // ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(7 * ncols, 5.2 * nrows), squeeze=False)
    axes = axes.ravel()
    for ax in axes[len(images):]:
        ax.axis("off")
    for ax, img, title in zip(axes, images, titles):
        ax.imshow(mpimg.imread(str(img)))
        ax.set_title(title)
        ax.axis("off")
    if suptitle:
        fig.suptitle(suptitle)
    fig.tight_layout()
    return savefig(fig, path)
