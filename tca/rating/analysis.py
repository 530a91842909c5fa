r"""Load factors from a loaded tooth contact analysis, to set beside ISO 6336-1's (numbers in, records out).

Face load factor (ISO 6336-1 defines :math:`K_{H\beta}` as the maximum load per unit face width over the mean).
The loaded TCA gives, at positions :math:`t_j` through one mesh cycle, the load :math:`F_s` of every slice
:math:`s` of every contact line at axial position :math:`z_s`. The face width :math:`[-b/2, b/2]` is cut into
:math:`N` equal bins of width :math:`\Delta z = b/N`; the load per unit face width of bin :math:`i`, summed over
all pairs of teeth in contact and averaged over the cycle, is

.. math::
    \bar w_i = \frac{1}{J}\sum_j \frac{1}{\Delta z}\sum_{s \in i} F_s(t_j), \qquad
    K_{H\beta} = \frac{\max_i \bar w_i}{\frac1N\sum_i \bar w_i} \quad (A1)

The average over the cycle is what makes (A1) the factor of the face alone: at one instant the load per unit face
width of a helical pair also varies with the number of contact lines crossing a section (one or two for
:math:`\varepsilon_\alpha = 1.5`), a transverse effect (K_Hα's) that averages out over a cycle. The largest
instantaneous ratio :math:`\max_j \max_i w_i(t_j)/\bar w(t_j)` is reported beside it.

Transverse load factor (ISO: the actual load of the most loaded pair of teeth against the load it would carry if
the pairs shared in proportion to their contact lengths). With :math:`s_q(t_j)` the load share of pair :math:`q`
and :math:`L_q(t_j)` the length of its contact line on both flanks,

.. math::
    K_{H\alpha} = \frac{\max_j \max_q s_q(t_j)/L_q(t_j)}{\max_j 1/\sum_q L_q(t_j)} \quad (A2)

the largest load per unit length of any pair through the cycle over the largest of the ideal (length-proportional)
sharing. For a spur pair the governing load is the single-contact load of both (A2 = 1 for error-free gears,
as ISO's K_Hα = 1 for accurate gears); pitch errors or relief that load one pair beyond its share raise it.
(A2) is never below 1: at every position the shares sum to 1, so some pair carries at least :math:`1/\sum_q L_q` per
unit length (ISO limits its K_Hα below by 1 as well).

Mesh load factor K_γ (a planetary train's most loaded planet over the mean) is passed in as a number from the
train's analysis: :class:`AnalysisFactors`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from tca.rating.errors import RatingInputError, check_range
from tca.rating.factors import Given
from tca.rating.rating import RatingCase

__all__ = ["FaceLoadAnalysis", "TransverseAnalysis", "AnalysisFactors", "face_load_from_slices",
           "transverse_from_shares", "with_analysis"]


@dataclass(frozen=True)
class FaceLoadAnalysis:
    """(A1): K_Hβ, the cycle-mean load per unit face width per bin [N/mm] and the largest instantaneous ratio."""

    k_h_beta: float
    z: np.ndarray  # bin centres [mm]
    line_load: np.ndarray  # w̄_i [N/mm]
    instantaneous: float  # max_j max_i w_i(t_j) / mean_i w_i(t_j)
    positions: int


@dataclass(frozen=True)
class TransverseAnalysis:
    """(A2): K_Hα (>= 1) and its unlimited value."""

    k_h_alpha: float
    unlimited: float
    positions: int


@dataclass(frozen=True)
class AnalysisFactors:
    """Factors computed by gearfe's analysis (each a :class:`Given` with source "gearfe", or None: ISO's)."""

    k_h_beta: Given | None = None
    k_h_alpha: Given | None = None
    k_gamma: Given | None = None

    def __post_init__(self):
        for k in ("k_h_beta", "k_h_alpha", "k_gamma"):
            g = getattr(self, k)
            if g is not None and not isinstance(g, Given):
                raise RatingInputError(k, g, "a Given record or None")

    def items(self):
        """(RatingCase field, Given) of the factors present."""
        return [(k, getattr(self, k)) for k in ("k_h_beta", "k_h_alpha", "k_gamma") if getattr(self, k) is not None]


def face_load_from_slices(position: np.ndarray, z: np.ndarray, force: np.ndarray, face_width: float,
                          bins: int, extent: np.ndarray | None = None) -> FaceLoadAnalysis:
    """(A1) from slice records: ``position`` index j, axial position ``z`` [mm] (face centre 0), load [N].

    ``extent``: half the axial length [mm] each slice covers; its load is spread uniformly over it and shared by the
    bins it overlaps (without it, by its centre: then bins narrower than the slices alias).
    """
    position, z, force = (np.asarray(a, float).ravel() for a in (position, z, force))
    if not (len(position) == len(z) == len(force)) or len(z) == 0:
        raise RatingInputError("slices", len(z), "equal, non-empty arrays of position, z and force")
    check_range("face_width", face_width, 0.0, lo_open=True)
    if int(bins) != bins or bins < 2:
        raise RatingInputError("bins", bins, "an integer >= 2")
    h = face_width / bins
    pos, j = np.unique(position, return_inverse=True)
    w = np.zeros((len(pos), bins))
    if extent is None:
        i = np.clip(np.floor((z + 0.5 * face_width) / h).astype(int), 0, bins - 1)
        np.add.at(w, (j, i), force / h)
    else:
        e = np.maximum(np.asarray(extent, float).ravel(), 1e-9)
        if len(e) != len(z):
            raise RatingInputError("extent", len(e), f"one half-length per slice ({len(z)})")
        lo = np.clip(z - e, -0.5 * face_width, 0.5 * face_width)[:, None]
        hi = np.clip(z + e, -0.5 * face_width, 0.5 * face_width)[:, None]
        edges = -0.5 * face_width + h * np.arange(bins + 1)
        part = np.clip(np.minimum(hi, edges[1:]) - np.maximum(lo, edges[:-1]), 0.0, None)  # (S, N) overlaps [mm]
        cover = part.sum(axis=1, keepdims=True)
        share = np.divide(part, cover, out=np.zeros_like(part), where=cover > 0)
        np.add.at(w, j, share * (force / h)[:, None])
    mean_t = w.mean(axis=1)
    ok = mean_t > 0
    if not ok.any():
        raise RatingInputError("force", 0.0, "slices carrying load (> 0 N)")
    inst = float((w[ok].max(axis=1) / mean_t[ok]).max())
    wb = w[ok].mean(axis=0)
    return FaceLoadAnalysis(float(wb.max() / wb.mean()), -0.5 * face_width + h * (np.arange(bins) + 0.5), wb, inst,
                            int(ok.sum()))


def transverse_from_shares(shares: np.ndarray, lengths: np.ndarray) -> TransverseAnalysis:
    """(A2) from ``shares`` and contact ``lengths`` [mm] of shape (positions, pairs) (0 where a pair is absent)."""
    s, L = np.asarray(shares, float), np.asarray(lengths, float)
    if s.shape != L.shape or s.ndim != 2 or s.size == 0:
        raise RatingInputError("shares", s.shape, "arrays of one shape (positions, pairs)")
    tot = L.sum(axis=1)
    ok = tot > 0
    if not ok.any():
        raise RatingInputError("lengths", 0.0, "contact lines of positive length")
    with np.errstate(divide="ignore", invalid="ignore"):
        per = np.where(L > 0, s / np.where(L > 0, L, 1.0), 0.0)
    k = float(per[ok].max() / (1.0 / tot[ok]).max())
    return TransverseAnalysis(max(1.0, k), k, int(ok.sum()))


def with_analysis(case: RatingCase, factors: AnalysisFactors) -> RatingCase:
    """``case`` with gearfe's factors in place of ISO's methods (K_Fβ follows K_Hβ by (F4), K_Fα = K_Hα)."""
    return replace(case, **dict(factors.items()))


