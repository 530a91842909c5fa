"""Result of the train TCA: trajectories, carrier transmission errors (Eq. 3.23) and their analysis.

The sun-centre trajectory is summarised by its best-fit circle (algebraic fit refined by Gauss-Newton on
the distances); the period of the carrier TE by a least-squares scan of sinusoids.
"""

from __future__ import annotations

from tca.units import ARCSEC

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from tca.isostatic.dof import DOFCount
from tca.isostatic.train import IsostaticTrain

__all__ = ["IsostaticResult", "fit_circle", "dominant_period", "ARCSEC"]



def fit_circle(p: np.ndarray) -> tuple[np.ndarray, float]:
    """Best-fit circle (centre (2,), radius) of points (n, 2): algebraic fit refined by Gauss-Newton on distances."""
    p = np.asarray(p, float)
    if len(p) < 3:
        return p.mean(0), 0.0
    scale = max(float(np.abs(p - p.mean(0)).max()), 1e-300)
    q = (p - p.mean(0)) / scale
    A = np.c_[q, np.ones(len(q))]
    b = (q**2).sum(1)
    sol, *_ = np.linalg.lstsq(A, b, rcond=None)
    c = sol[:2] / 2
    r2 = sol[2] + c @ c
    if not (r2 > 0) or np.linalg.matrix_rank(A, 1e-9) < 3:
        return p.mean(0), 0.0
    r = math.sqrt(r2)
    for _ in range(20):  # geometric refinement
        d = q - c
        L = np.linalg.norm(d, axis=1)
        if np.any(L == 0):
            break
        res = L - r
        Jm = np.c_[-d / L[:, None], -np.ones(len(q))]
        step, *_ = np.linalg.lstsq(Jm, -res, rcond=None)
        c, r = c + step[:2], r + step[2]
        if np.abs(step).max() < 1e-14:
            break
    return c * scale + p.mean(0), abs(r) * scale


def dominant_period(x: np.ndarray, y: np.ndarray, span: float) -> float | None:
    """Period of the strongest sinusoid in y(x): least-squares fit of a + b cos + c sin over a scan of periods [units of x]."""
    y = np.asarray(y, float) - np.mean(y)
    if np.ptp(y) == 0 or len(x) < 8:
        return None

    def power(P):
        w = 2 * math.pi * x / P
        A = np.c_[np.ones_like(w), np.cos(w), np.sin(w)]
        c, *_ = np.linalg.lstsq(A, y, rcond=None)
        return float(np.sum((A[:, 1:] @ c[1:]) ** 2))

    dx = float(np.median(np.diff(x)))
    f = np.linspace(1 / span, min(40 / span, 0.25 / dx), 800)  # frequencies
    pw = np.array([power(1 / fi) for fi in f])
    k = int(np.argmax(pw))
    lo, hi = f[max(k - 1, 0)], f[min(k + 1, len(f) - 1)]
    g = (math.sqrt(5) - 1) / 2
    a, b = lo, hi
    for _ in range(60):  # golden-section refinement of the peak
        c1, c2 = b - g * (b - a), a + g * (b - a)
        if power(1 / c1) > power(1 / c2):
            b = c2
        else:
            a = c1
    return 2 / (a + b)


@dataclass(frozen=True, eq=False)
class IsostaticResult:
    """Configuration of the train at every sun angle."""

    train: IsostaticTrain
    options: Any  # tca.isostatic.analysis.IsostaticOptions
    phi1: np.ndarray  # (n,) [rad]
    phi_c: np.ndarray  # (n,) carrier angle [rad]
    phi_c_planets: np.ndarray  # (n, Np) carrier angle of each subtrain (equal unless rigid hyperstatic)
    te: np.ndarray  # (n,) Delta phi_c = phi_c - m_c1 phi1 (Eq. 3.23) [rad]
    sun_center: np.ndarray  # (n, 2) [mm]
    carrier_center: np.ndarray  # (n, 2) [mm]
    ring_center: np.ndarray  # (n, 2) [mm]
    phi2: np.ndarray  # (n, Np) planet rotation relative to the carrier [rad]
    teeth: np.ndarray  # (n, Np, 4) contacting teeth: sun, planet (sun side), planet (ring side), ring (mod N)
    params: np.ndarray  # (n, Np, 4) u of the four flanks at the contacts [mm]
    point_s: np.ndarray  # (n, Np, 2) sun-planet contact point in S_f [mm]
    point_r: np.ndarray  # (n, Np, 2) planet-ring contact point in S_f [mm]
    margin: np.ndarray  # (n, Np, 2) depth of the contacts inside the working areas [mm]
    backlash: np.ndarray  # (n, Np, 2, 2) backlash of the neighbouring pairs (mesh s/r, previous/next) [mm]
    planet_backlash: np.ndarray  # (n, Np) backlash of a planet's loop along the sun's line of action [mm]
    residual: np.ndarray  # (n,) max |F| of Eq. (3.18) over the subtrains [mm]
    outer_iterations: np.ndarray  # (n,) iterations of Eq. (3.22)
    rounds: int  # rounds of contact switching
    rigid: bool  # all axes fixed and more planets than isostatic: planets may keep a backlash
    dof: DOFCount
    elapsed: float
    _cache: dict = field(default_factory=dict, repr=False)

    @property
    def te_arcsec(self) -> np.ndarray:
        return self.te / ARCSEC

    @property
    def carrier_te_peak_to_peak_arcsec(self) -> float:
        return float(np.ptp(self.te_arcsec))

    @property
    def carrier_lag_mean_arcsec(self) -> float:
        """Mean lag of the carrier, -mean(Delta phi_c) (positive: lagging) [arcsec]."""
        return float(-self.te_arcsec.mean())

    @property
    def sun_center_um(self) -> np.ndarray:
        return self.sun_center * 1e3

    @property
    def sun_circle(self) -> tuple[np.ndarray, float]:
        """Best-fit circle of the sun centre trajectory: centre [um], radius [um]."""
        if "circle" not in self._cache:
            self._cache["circle"] = fit_circle(self.sun_center_um)
        return self._cache["circle"]

    @property
    def all_planets_in_contact(self) -> bool:
        """Every planet touches sun and ring at every position (within 1 nm of loop backlash)."""
        return bool(np.all(self.planet_backlash < 1e-6) and np.all(self.margin >= -self.options.area_tol))

    @property
    def transitions(self) -> int:
        """Changes of the contacting pair over the run, all meshes."""
        return int(np.sum(np.any(np.diff(self.teeth, axis=0) != 0, axis=-1)))

    @property
    def positions_per_mesh_cycle(self) -> float | None:
        """Sampling of the mesh cycles (a sun-mesh cycle is 1 / ((1 - m_c1) N1) sun revolutions)."""
        if len(self.phi1) < 2:
            return None
        step = float(np.median(np.abs(np.diff(self.phi1)))) / (2 * math.pi)
        return 1.0 / (step * (1 - self.train.ratio) * self.train.sun.teeth)

    def te_period_sun_rev(self) -> float | None:
        """Period of the strongest harmonic of the carrier TE [sun revolutions] (None if the TE is flat)."""
        if self.carrier_te_peak_to_peak_arcsec < 1e-3:
            return None
        rev = (self.phi1 - self.phi1[0]) / (2 * math.pi)
        span = float(rev[-1] + (rev[1] - rev[0] if len(rev) > 1 else 1.0))
        return dominant_period(rev, self.te_arcsec, span)

    def summary(self) -> dict:
        """Key numbers (JSON-ready)."""
        c, r = self.sun_circle
        per = self.te_period_sun_rev()
        mag = np.linalg.norm(self.sun_center_um, axis=1)
        return {
            "carrier_lag_mean_arcsec": self.carrier_lag_mean_arcsec,
            "carrier_te_mean_arcsec": float(self.te_arcsec.mean()),
            "carrier_te_peak_to_peak_arcsec": self.carrier_te_peak_to_peak_arcsec,
            "carrier_te_min_arcsec": float(self.te_arcsec.min()),
            "carrier_te_max_arcsec": float(self.te_arcsec.max()),
            "te_period_sun_rev": per,
            "sun_center_max_um": float(mag.max()),
            "sun_center_min_um": float(mag.min()),
            "sun_center_radius_um": float(r),
            "sun_center_circle_center_um": [float(c[0]), float(c[1])],
            "sun_center_peak_to_peak_um": [float(np.ptp(self.sun_center_um[:, 0])), float(np.ptp(self.sun_center_um[:, 1]))],
            "all_planets_in_contact": self.all_planets_in_contact,
            "planet_backlash_max_um": (self.planet_backlash.max(0) * 1e3).tolist(),
            "dof": self.dof.as_dict(),
            "rigid_hyperstatic": self.rigid,
            "planets": self.train.n_planets,
            "ratio_mc1": self.train.ratio,
            "positions": int(len(self.phi1)),
            "sun_revolutions": float((self.phi1[-1] - self.phi1[0]) / (2 * math.pi)) if len(self.phi1) > 1 else 0.0,
            # below ~8, harmonics of the mesh frequency alias (the TE period then reflects the sampling)
            "positions_per_mesh_cycle": self.positions_per_mesh_cycle,
            "transitions": self.transitions,
            "switch_rounds": self.rounds,
            "min_contact_margin_mm": float(self.margin.min()),
            "max_residual_mm": float(self.residual.max()),
            "outer_iterations_max": int(self.outer_iterations.max()),
            "method": self.options.method,
            "elapsed_s": self.elapsed,
        }


# ---------------------------------------------------------------------------------------------
