"""The distribution of K_γ over the samples of a train tolerance sweep (:mod:`pipelines.sweep.trains`): a histogram
and the empirical cumulative distribution, with the mean and the 95th percentile marked."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pipelines.render.plots import plt, savefig

__all__ = ["plot_k_gamma_distribution"]


def plot_k_gamma_distribution(values: dict, out: Path, title: str = "") -> str:
    """``k_gamma_distribution.png`` in ``out``: per quantity (label -> sample values, e.g. K_γ and the members'
    K_γ of a twin train) a histogram (left) and the empirical CDF (right); its file name."""
    name = "k_gamma_distribution.png"
    fig, (h, c) = plt.subplots(1, 2, figsize=(10, 3.8))
    for k, (label, v) in enumerate(values.items()):
        v = np.sort(np.asarray(v, float))
        col = f"C{k % 10}"
        h.hist(v, bins=max(5, min(40, len(v) // 5)), color=col, alpha=0.55, label=label)
        c.step(v, np.arange(1, len(v) + 1) / len(v), where="post", color=col, label=label)
        mean, p95 = float(v.mean()), float(np.percentile(v, 95))
        for a in (h, c):
            a.axvline(mean, color=col, lw=0.8, ls="--")
            a.axvline(p95, color=col, lw=0.8, ls=":")
        c.annotate(f"mean {mean:.4f}, 95 % {p95:.4f}", (0.02, 0.92 - 0.08 * k), xycoords="axes fraction",
                   color=col, fontsize=8)
    h.set_xlabel("K_gamma")
    h.set_ylabel("samples")
    c.set_xlabel("K_gamma")
    c.set_ylabel("fraction of samples <= K_gamma")
    c.axhline(0.95, color="k", lw=0.5, ls=":")
    for a in (h, c):
        a.grid(alpha=0.3)
        a.legend(fontsize=8, loc="lower right" if a is c else "upper right")
    n = len(next(iter(values.values())))
    fig.suptitle(f"{title}: {n} samples (dashed: mean, dotted: 95th percentile)" if title else
                 f"{n} samples (dashed: mean, dotted: 95th percentile)", fontsize=9)
    savefig(fig, Path(out) / name)
    return name
