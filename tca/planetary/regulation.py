r"""Twin subgear drives, integrated TE of the planetary train and regulation of backlash (1.3–1.5).

Twin subgear drive of shaft *i* (Eq. 1.15): members *a* and *b* are solved independently (each a
single subgear drive, :mod:`tca.planetary.subgear`) and the ring follows the member that is ahead,

.. math:: \Delta\phi_3^{(i)}(\phi_1) = \max\{\Delta\phi_{3a}^{(i)}(\phi_1), \Delta\phi_{3b}^{(i)}(\phi_1)\}.

Without a shaft-angle error the members are mirror images (and so are their errors and a
mirror-symmetric regulation), so member *b* repeats member *a* and is not recomputed.

Integrated TE of the train (section 1.5): all absolute functions :math:`\Delta\phi_3^{(i)}` are
measured from one zero-backlash configuration, so at each :math:`\phi_1` the planet with the
largest value is in mesh and each other planet has the backlash
:math:`|M_jM_i| = \max_l \Delta\phi_3^{(l)} - \Delta\phi_3^{(i)}` (Fig. 1.4(a)).

Regulation (Numerical Examples 1.1 and 1.2). Criterion: every member's TE function reaches the
same maximum as the error-free member (the peak of its function, where it engages with zero
backlash): :math:`g(\Delta Z) = \max_{\phi_1}\Delta\phi_{3k}^{(i)}(\phi_1;\Delta Z) - \max_{\phi_1}
\Delta\phi_3^{\rm nominal} = 0`. :math:`\Delta Z^{(1)}` (Eq. 1.16, for the member's tangential
displacement :math:`\Delta E_x + s_k z_m\sin\Delta\gamma`) starts a secant iteration on TCA
results; :math:`\Delta Z^{(2)}` is its root. The spread of the train is
:math:`\max_i P_i - \min_i P_i` over the planets' maxima :math:`P_i`.

The criterion compares maxima because the functions of different planets are phase-shifted copies
(by :math:`\theta_i`, and an axial shift also moves a member's function by about
:math:`\Delta Z\tan\beta_1/r_1` in :math:`\phi_1`): the maximum, like the mean, is invariant to a
phase shift. Under Δγ the members' functions are also shifted in phase by the tilt (the parabola
absorbs the linear error, Litvin's point), so members *a* and *b* reach equal maxima but do not
coincide pointwise; their axes are tilted, so ΔZ along them also moves them tangentially by
:math:`\Delta Z\sin\Delta\gamma`, which changes their sensitivity to ΔZ (secant, not Eq. 1.16).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from tca.errors import ConvergenceError, InputError
from tca.pair.analysis import ARCSEC, TCAOptions
from tca.planetary.train import DoubleHelicalTrain, ShaftErrors, dz_first_order
from tca.planetary.subgear import SubgearTE, periodic_peak, phi1_grid, run_subgear_tca

__all__ = ["TwinTE", "TrainTE", "RegulationOptions", "MemberRegulation", "TrainRegulation", "periodic_peak", "twin_te",
           "integrated_te", "nominal_peak", "regulate_member", "regulate_train", "member_d_ex"]


@dataclass(frozen=True, eq=False)
class TwinTE:
    """Twin subgear drive of one shaft: members a and b and Eq. (1.15)."""

    shaft: int  # 0-based
    members: dict  # 'a'/'b' -> SubgearTE
    mirrored: bool  # member b is the mirror image of a (not recomputed)

    @property
    def phi1(self) -> np.ndarray:
        return self.members["a"].phi1

    @property
    def te(self) -> np.ndarray:
        """Δφ3 of the twin drive, Eq. (1.15) [rad]."""
        return np.maximum(self.members["a"].te3, self.members["b"].te3)

    @property
    def peak(self) -> float:
        return periodic_peak(self.te)


def member_d_ex(train: DoubleHelicalTrain, member: str, errors: ShaftErrors) -> float:
    """Tangential displacement of a member's centre, in the sense of ΔE_x [mm] (Δγ about the shaft centre)."""
    return errors.d_ex + train.member_sign(member) * train.member_offset * math.sin(errors.d_gamma)


def twin_te(train: DoubleHelicalTrain, i: int, errors: ShaftErrors = ShaftErrors(), dz=(0.0, 0.0),
            opts: TCAOptions = TCAOptions(), cache: dict | None = None, mirror: bool = True) -> TwinTE:
    """Twin drive of shaft i at axial regulations dz = (ΔZ_a, ΔZ_b) [mm]; b mirrored when allowed."""
    phi1 = phi1_grid(train, opts)
    a = run_subgear_tca(train, i, "a", errors, dz[0], opts, phi1, cache)
    if mirror and errors.d_gamma == 0.0 and dz[0] == dz[1]:
        return TwinTE(i, {"a": a, "b": a}, True)
    b = run_subgear_tca(train, i, "b", errors, dz[1], opts, phi1, cache)
    return TwinTE(i, {"a": a, "b": b}, False)


@dataclass(frozen=True, eq=False)
class TrainTE:
    """Integrated TE of the train: all twin drives on one φ1 grid."""

    twins: tuple  # TwinTE per shaft

    @property
    def phi1(self) -> np.ndarray:
        return self.twins[0].phi1

    @property
    def te(self) -> np.ndarray:
        """(n, m) Δφ3 of every twin drive [rad]."""
        return np.stack([t.te for t in self.twins])

    @property
    def integrated(self) -> np.ndarray:
        """Δφ3 of the train: the planet that is ahead drives [rad]."""
        return self.te.max(0)

    @property
    def in_mesh(self) -> np.ndarray:
        """0-based shaft in mesh at each φ1."""
        return np.argmax(self.te, 0)

    @property
    def backlash(self) -> np.ndarray:
        """(n, m) backlash |M_j M_i| of every planet to the planet in mesh [rad]."""
        return self.integrated[None, :] - self.te

    @property
    def peaks(self) -> np.ndarray:
        return np.array([t.peak for t in self.twins])

    @property
    def spread(self) -> float:
        """max_i P_i - min_i P_i over the planets' maxima [rad]."""
        p = self.peaks
        return float(p.max() - p.min())

    def summary(self) -> dict:
        te = self.te / ARCSEC
        second = np.sort(te, 0)[-2] if len(te) > 1 else np.full(te.shape[1], -np.inf)
        return {
            "peaks_arcsec": (self.peaks / ARCSEC).tolist(),
            "spread_arcsec": self.spread / ARCSEC,
            "planets_in_mesh": sorted({int(k) + 1 for k in self.in_mesh}),
            "min_margin_to_next_planet_arcsec": float(np.min(te.max(0) - second)),
            "max_backlash_arcsec": float(self.backlash.max() / ARCSEC),
            "integrated_peak_to_peak_arcsec": float(np.ptp(self.integrated) / ARCSEC),
        }


def integrated_te(twins) -> TrainTE:
    """Integrated TE of the train from the twin drives of all shafts."""
    twins = tuple(twins)
    if not twins:
        raise InputError("twins", 0, "at least one twin drive")
    return TrainTE(twins)


def nominal_peak(train: DoubleHelicalTrain, opts: TCAOptions = TCAOptions(), cache: dict | None = None) -> float:
    """Maximum of Δφ3 of an error-free member at its nominal axial position [rad]: the regulation target."""
    return periodic_peak(run_subgear_tca(train, 0, "a", ShaftErrors(), 0.0, opts, cache=cache).te3)


@dataclass(frozen=True)
class RegulationOptions:
    """Stopping rule of the secant on ΔZ: the TE maximum within ``tol`` [rad] of the target, at most ``maxiter``
    TCA evaluations of a member."""

    tol: float = 1e-3 * ARCSEC
    maxiter: int = 12


@dataclass(frozen=True, eq=False)
class MemberRegulation:
    """Axial regulation of one member: ΔZ^(1) (Eq. 1.16), ΔZ^(2) (TCA) and the secant history."""

    shaft: int
    member: str
    dz1: float  # [mm]
    dz2: float  # [mm]
    history: tuple  # ((dz [mm], g [rad]), ...)
    before: SubgearTE
    first_order: SubgearTE
    after: SubgearTE

    @property
    def iterations(self) -> int:
        return len(self.history)


def regulate_member(train: DoubleHelicalTrain, i: int, member: str, errors: ShaftErrors, target: float,
                    opts: TCAOptions = TCAOptions(), regulation: RegulationOptions = RegulationOptions(),
                    cache: dict | None = None) -> MemberRegulation:
    """ΔZ^(2) of member (shaft i, 'a'/'b') making its TE maximum equal `target` [rad]: secant on TCA results."""
    tol, maxiter = regulation.tol, regulation.maxiter
    phi1 = phi1_grid(train, opts)

    def g(dz):
        r = run_subgear_tca(train, i, member, errors, dz, opts, phi1, cache)
        return periodic_peak(r.te3) - target, r

    g0, before = g(0.0)
    dz1 = dz_first_order(train, member_d_ex(train, member, errors))
    hist = [(0.0, g0)]
    if abs(g0) < tol:
        return MemberRegulation(i, member, dz1, 0.0, tuple(hist), before, before if dz1 == 0 else g(dz1)[1], before)
    g1, first = g(dz1) if dz1 != 0.0 else (g0, before)
    hist.append((dz1, g1))
    x0, f0, x1, f1, cur = 0.0, g0, dz1, g1, first
    if dz1 == 0.0:  # no first-order guess: step with the first-order slope dP/dΔZ = (tan β1 - tan β3)/r3
        slope = (math.tan(train.sun.helix) - math.tan(train.ring.helix)) / train.ring.r_p
        x1 = -g0 / slope
        f1, cur = g(x1)
        hist.append((x1, f1))
    while abs(f1) >= tol:
        if len(hist) >= maxiter:
            raise ConvergenceError("axial regulation (TE maximum off target, arcsec)", f"shaft {i + 1} member {member}",
                                   abs(f1) / ARCSEC, len(hist))
        if f1 == f0:
            raise ConvergenceError("axial regulation (TE maximum does not change with Delta Z, arcsec)", f"shaft {i + 1} member {member}",
                                   abs(f1) / ARCSEC, len(hist))
        x2 = x1 - f1 * (x1 - x0) / (f1 - f0)
        if abs(x2) > 0.5 * train.planet.face_width:
            raise ConvergenceError("axial regulation (TE maximum off target, arcsec)",
                                   f"shaft {i + 1} member {member}: Delta Z = {x2:.3f} mm beyond half the face width",
                                   abs(f1) / ARCSEC, len(hist))
        f2, cur = g(x2)
        hist.append((x2, f2))
        x0, f0, x1, f1 = x1, f1, x2, f2
    return MemberRegulation(i, member, dz1, x1, tuple(hist), before, first, cur)


@dataclass(frozen=True, eq=False)
class TrainRegulation:
    """Regulation of every member of the train and the integrated TE before, with ΔZ^(1), with ΔZ^(2)."""

    train: DoubleHelicalTrain
    errors: tuple  # ShaftErrors per shaft
    target: float  # [rad]
    members: tuple  # ((MemberRegulation a, MemberRegulation b), ...) per shaft
    before: TrainTE
    first_order: TrainTE
    after: TrainTE
    elapsed: float  # wall time [s]
    cpu: float  # process time [s]
    tca_runs: int  # member evaluations (each two pair TCAs)


def regulate_train(train: DoubleHelicalTrain, errors, opts: TCAOptions = TCAOptions(),
                   regulation: RegulationOptions = RegulationOptions(), progress=None) -> TrainRegulation:
    """Regulate all 2n members (mirror images computed once) and integrate the TE of the train.

    ``progress(message)`` is called after each shaft (e.g. ``print``).
    """
    t0, c0 = time.perf_counter(), time.process_time()
    errors = tuple(errors)
    if len(errors) != train.planets:
        raise InputError("installment", len(errors), f"errors for each of the {train.planets} planet shafts")
    if any(e != ShaftErrors() for e in errors):
        dz_first_order(train, 0.0)  # regulation needs beta1 != beta3: fail before any TCA
    cache: dict = {}
    target = nominal_peak(train, opts, cache)
    regs, before, first, after = [], [], [], []
    for i, e in enumerate(errors):
        ra = regulate_member(train, i, "a", e, target, opts, regulation, cache)
        rb = ra if e.d_gamma == 0.0 else regulate_member(train, i, "b", e, target, opts, regulation, cache)
        regs.append((ra, rb))
        mir = rb is ra
        before.append(TwinTE(i, {"a": ra.before, "b": rb.before}, mir))
        first.append(TwinTE(i, {"a": ra.first_order, "b": rb.first_order}, mir))
        after.append(TwinTE(i, {"a": ra.after, "b": rb.after}, mir))
        if progress is not None:
            progress(f"planet {i + 1}/{len(errors)}: dZ(1) = {ra.dz1:+.4f} mm, dZ(2) = {ra.dz2:+.4f} mm"
                     + ("" if mir else f" (a), {rb.dz2:+.4f} mm (b)")
                     + f"  [{time.perf_counter() - t0:.1f} s]")
    return TrainRegulation(train, errors, target, tuple(regs), integrated_te(before), integrated_te(first),
                           integrated_te(after), time.perf_counter() - t0, time.process_time() - c0, len(cache))

