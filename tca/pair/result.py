"""Results and options of a pair TCA: contact kinds, resolution, the reference-pair solution, the result over the cycles."""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import IntEnum

import numpy as np

from tca.errors import InputError
from tca.pair.gear_pair import GearPair
from tca.units import ARCSEC

__all__ = ["ContactKind", "TCAOptions", "ReferencePairSolution", "PairTCAResult", "ellipse_outlines", "ARCSEC"]


class ContactKind(IntEnum):
    """How a pair of teeth touches at a position (section 1.4, step 2)."""

    NONE = 0
    SURFACE = 1  # point of tangency inside both working areas
    EDGE = 2  # a boundary of one working area touches the other surface
    CORNER = 3  # two boundaries touch (edge against edge)
    FILLET = 4  # the tangency lies below the start of the fillet: interference


ContactKind.names = {int(k): k.name.lower() for k in ContactKind}  # value -> "surface", ...


@dataclass(frozen=True)
class TCAOptions:
    """Resolution and tolerances of a pair TCA."""

    cycles: int = 2
    steps_per_cycle: int = 40
    elastic_approach: float = 0.0065  # [mm], for the contact ellipse
    tol: float = 1e-11  # Newton target on residuals [mm]
    max_residual: float = 1e-10  # verification of every converged point [mm]
    coarse_per_cycle: int = 10  # sequential continuation points per cycle; the rest are solved in one batch
    area_tol: float = 1e-7  # [mm] a point on a boundary counts as inside

    def __post_init__(self):
        if not (isinstance(self.cycles, int) and 1 <= self.cycles <= 50):
            raise InputError("tca.cycles", self.cycles, "an integer in [1, 50]")
        if not (isinstance(self.steps_per_cycle, int) and 4 <= self.steps_per_cycle <= 2000):
            raise InputError("tca.steps_per_cycle", self.steps_per_cycle, "an integer in [4, 2000]")
        if not (0 < self.elastic_approach < 1):
            raise InputError("tca.elastic_approach_mm", self.elastic_approach, "in (0, 1) mm")
        if not (isinstance(self.coarse_per_cycle, int) and 2 <= self.coarse_per_cycle):
            raise InputError("tca.coarse_per_cycle", self.coarse_per_cycle, "an integer >= 2")

    @property
    def coarse_every(self) -> int:
        """Stride of the sequential continuation on the fine grid."""
        return max(1, round(self.steps_per_cycle / self.coarse_per_cycle))


@dataclass(frozen=True, eq=False)
class ReferencePairSolution:
    """Contact of the reference pair of teeth on the grid phi1 = phi1_0 + j h."""

    phi1: np.ndarray  # (n,)
    phi2: np.ndarray  # (n,), -inf where no contact
    x: np.ndarray  # (n, 5) u1, v1, u2, v2, phi2
    kind: np.ndarray  # (n,) ContactKind
    residual: np.ndarray  # (n,)
    where: np.ndarray  # (n,) boundary code: 10*flank + boundary for edges, 100*flank + 10*a + b for corners
    j: np.ndarray  # (n,) grid index
    newton_iterations: int
    tangency: np.ndarray  # (n,) a point of tangency of the extended surfaces was found
    out_of_mesh: np.ndarray  # (n,) beyond the position where the pair was seen to leave its mesh


@dataclass(frozen=True, eq=False)
class PairTCAResult:
    """Pair TCA over `cycles` cycles: per-position arrays and the reference-pair curve."""

    pair: GearPair
    options: TCAOptions
    phi1: np.ndarray
    phi2: np.ndarray
    te: np.ndarray  # Delta phi2 [rad]
    active_pair: np.ndarray  # index k of the pair in contact
    kind: np.ndarray
    point_f: np.ndarray  # contact point in S_f [mm]
    params: np.ndarray  # (n, 4) u1, v1, u2, v2 on the reference teeth
    point1: np.ndarray  # contact point on tooth surface 1, gear-1 frame [mm]
    point2: np.ndarray  # contact point on tooth surface 2, gear-2 frame [mm]
    ellipse_a: np.ndarray  # semi-major axis [mm]
    ellipse_b: np.ndarray  # semi-minor axis [mm]
    ellipse_angle: np.ndarray  # major axis from the projected gear-1 axis [rad]
    residual: np.ndarray
    reference: ReferencePairSolution
    transitions: np.ndarray  # phi1 at which the pair in contact changes [rad]
    elapsed: float
    boundary: np.ndarray  # where edge/corner contact is: 10 flank + boundary (1 tip, 2 z_max, 3 z_min),
    #                       100 flank + 10 boundary + end for corners, 1000 + 10 b1 + b2 for edge-to-edge
    transition_te: np.ndarray  # TE at the transitions [rad] (both pairs in contact there)
    te_extremes: tuple  # (min, max) of the TE function [rad]: grid, exact transitions, refined vertices

    def edge_boundaries(self) -> set[int]:
        """Working-area boundaries (1 tip, 2 z_max, 3 z_min) that carry edge or corner contact."""
        out = set()
        for w in self.boundary[(self.kind == ContactKind.EDGE) | (self.kind == ContactKind.CORNER)]:
            w = int(w)
            if w >= 1000:
                out |= {(w // 10) % 10, w % 10}
            elif w >= 100:
                out.add((w // 10) % 10)
            else:
                out.add(w % 10)
        return out

    @property
    def te_arcsec(self) -> np.ndarray:
        return self.te / ARCSEC

    @property
    def te_peak_to_peak_arcsec(self) -> float:
        """Peak-to-peak TE [arcsec], with the extremes at the exact transitions and refined vertices."""
        return float(self.te_extremes[1] - self.te_extremes[0]) / ARCSEC

    @property
    def edge_contact(self) -> bool:
        return bool(np.any((self.kind == ContactKind.EDGE) | (self.kind == ContactKind.CORNER)))

    @property
    def max_residual(self) -> float:
        return float(np.max(self.residual))

    def summary(self) -> dict:
        """Key numbers (JSON-ready)."""
        kinds = {ContactKind.names[k]: int(np.sum(self.kind == k)) for k in np.unique(self.kind)}
        finite_a = self.ellipse_a[np.isfinite(self.ellipse_a)]
        return {
            "te_peak_to_peak_arcsec": self.te_peak_to_peak_arcsec,
            "te_max_arcsec": float(self.te_extremes[1] / ARCSEC),
            "te_min_arcsec": float(self.te_extremes[0] / ARCSEC),
            "te_transitions_arcsec": [float(t / ARCSEC) for t in self.transition_te],
            "edge_contact": self.edge_contact,
            "contact_kinds": kinds,
            "positions": int(len(self.phi1)),
            "cycles": self.options.cycles,
            "transitions_deg": [math.degrees(t) for t in self.transitions],
            "max_residual_mm": self.max_residual,
            "line_contact": bool(np.any(np.isinf(self.ellipse_a) & (self.kind == ContactKind.SURFACE))),
            "ellipse_major_max_mm": float(finite_a.max()) if finite_a.size else None,
            "elapsed_s": self.elapsed,
        }


def ellipse_outlines(result: PairTCAResult, which: int, npts: int = 48) -> np.ndarray:
    """Contact ellipses as closed 3D outlines (n, npts, 3) in the frame of gear `which` (1 or 2).

    NaN where there is no ellipse (edge contact) or where it is unbounded (line contact).
    """
    pair = result.pair
    f1, f2 = pair.flanks()
    n = len(result.phi1)
    out = np.full((n, npts, 3), np.nan)
    ok = np.isfinite(result.ellipse_a) & np.isfinite(result.ellipse_b)
    if not ok.any():
        return out
    X = result.params[ok]
    ph1 = result.phi1[ok] - result.active_pair[ok] * 2 * math.pi / pair.gear1.teeth
    w1, _, _ = f1.world(X[:, 0], X[:, 1], ph1)
    ph2 = (result.phi2[ok] - result.active_pair[ok] * 2 * math.pi / pair.gear2.teeth)
    nrm = w1.n
    axis = np.broadcast_to(pair.mounts()[0].axis, nrm.shape)
    e1 = axis - np.einsum("ij,ij->i", axis, nrm)[:, None] * nrm
    e1 /= np.linalg.norm(e1, axis=-1, keepdims=True)
    e2 = np.cross(nrm, e1)
    ang = result.ellipse_angle[ok]
    A = np.cos(ang)[:, None] * e1 + np.sin(ang)[:, None] * e2  # major axis direction
    B = np.cross(nrm, A)
    t = np.linspace(0, 2 * math.pi, npts)
    pts = (w1.r[:, None, :] + result.ellipse_a[ok][:, None, None] * np.cos(t)[None, :, None] * A[:, None, :]
           + result.ellipse_b[ok][:, None, None] * np.sin(t)[None, :, None] * B[:, None, :])
    flank = f1 if which == 1 else f2
    phi = ph1 if which == 1 else ph2
    R, _, tt, _ = flank.frame(phi)
    out[ok] = np.einsum("nji,nkj->nki", R, pts - tt[:, None, :])
    return out
