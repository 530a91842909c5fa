r"""Multi-body TCA of a planar planetary train with floating members (section 3.3, Eqs. 3.18–3.23).

For every given sun angle :math:`\phi_1` the configuration of the whole train is found:

1. **Tooth numbering** (Fig. 3.2). Each mesh (sun–planet *i*, planet *i*–ring) has a pair of tooth
   indices. The first guess takes the teeth whose flanks' pitch points are nearest the mesh's
   pitch point in the nominal motion; points of contact are first guessed where the flanks cross
   the nominal line of action.
2. **Fictitious unknowns** (section 3.3.3). Each subtrain *i* gets its own carrier angle
   :math:`\phi_c^{(i)}`, and Eq. (3.18) (planar form, :mod:`tca.isostatic_mesh`) is solved for the
   given centres of the floating members (Newton, batched over positions and planets). The
   conditions of one rigid carrier, :math:`\phi_c^{(i)} - \phi_c^{(i+1)} = 0` (Eq. 3.22, :math:`N_p - 1`
   equations), are then solved by an outer Newton iteration for the floating centres (Eq. 3.21: the
   sun centre :math:`\Delta E_{1x}, \Delta E_{1y}` in case 2; also the carrier centre in case 3), with
   :math:`\partial\phi_c^{(i)}/\partial\mathbf E` from implicit differentiation of (3.18). A *direct*
   simultaneous Newton solve of all :math:`6N_p` equations is offered as a cross-check
   (``method="direct"``).
3. **Switching of the contacting pair** (Eqs. 3.19–3.20): with the solved poses, the backlash of the
   neighbouring pairs of every mesh is computed; a pair with negative backlash interferes, so it is the
   contacting pair: the indices move and the positions concerned are solved again, until no
   neighbour interferes. Pairs whose backlash is within ``tie_tol`` of the smallest are in contact
   together (involute gears share the load); the one deepest in both working areas is kept.
4. **Transmission errors** of the carrier (Eq. 3.23): :math:`\Delta\phi_c = \phi_c - m_{c1}\phi_1`,
   absolute (from the zero-backlash reference of :mod:`tca.isostatic_train`).

The train must be isostatic when a member floats (:mod:`tca.dof`). A hyperstatic train with all
axes fixed (e.g. case 1 constraints with 3 planets) is solved as a rigid train: the carrier takes
the largest :math:`\phi_c^{(i)}` (the first planet to touch) and the others keep a backlash.

Every Newton solve raises a :class:`~tca.errors.ConvergenceError` naming the position when it fails;
contact leaving the working areas (edge contact, not modelled in the plane) raises a
:class:`~tca.errors.GeometryError` naming the position and the mesh.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .dof import DOFCount
from .errors import ConvergenceError, GeometryError, InputError
from .isostatic_flank import apply, nearest_tooth, rot2
from .isostatic_mesh import (BODY_CARRIER, BODY_RING, BODY_SUN, JT_CENTRES, Members, Poses, TrainFlanks,
                             backlash_solve, corner_gap, line_crossing, mate_tooth, poses, subtrain_eval)
from .isostatic_train import PlanetaryTrain
from .newton import newton

__all__ = ["IsostaticOptions", "IsostaticResult", "run_isostatic_tca", "phi1_grid", "fit_circle", "dominant_period"]

ARCSEC = math.pi / (180 * 3600)
_BODY = {"sun": BODY_SUN, "carrier": BODY_CARRIER, "ring": BODY_RING}


@dataclass(frozen=True)
class IsostaticOptions:
    """Method and tolerances of the train TCA."""

    method: str = "fictitious"  # "fictitious" (Eqs. 3.21-3.22) or "direct" (all unknowns at once)
    tol: float = 1e-11  # Newton target on the residuals of Eq. (3.18) [mm]
    outer_tol: float = 1e-10  # r_c |phi_c^(i) - phi_c^(i+1)| at convergence of Eq. (3.22) [mm]
    tie_tol: float = 1e-8  # neighbouring pairs with backlash within this of the smallest touch together [mm]
    area_tol: float = 1e-6  # a point this far outside a working area still counts as inside [mm]
    max_outer: int = 30
    max_rounds: int = 12  # rounds of contact switching
    section_z: float = 0.0  # transverse section of contact [mm]

    def __post_init__(self):
        if self.method not in ("fictitious", "direct"):
            raise InputError("solver.method", self.method, "'fictitious' or 'direct'")
        for name, lo, hi in (("tol", 1e-14, 1e-6), ("outer_tol", 1e-13, 1e-4), ("tie_tol", 0.0, 1e-3),
                             ("area_tol", 0.0, 0.1)):
            v = getattr(self, name)
            if not (lo <= v <= hi):
                raise InputError(f"solver.{name}_mm", v, f"in [{lo:g}, {hi:g}] mm")
        for name in ("max_outer", "max_rounds"):
            v = getattr(self, name)
            if not (isinstance(v, int) and 1 <= v <= 200):
                raise InputError(f"solver.{name}", v, "an integer in [1, 200]")


def phi1_grid(train: PlanetaryTrain, positions: int, *, sun_revolutions: float | None = None,
              carrier_revolutions: float | None = None, planet_revolutions: float | None = None,
              start: float = 0.0) -> np.ndarray:
    """`positions` equally spaced sun angles over a span given in sun, carrier or planet (relative) turns [rad]."""
    given = {k: v for k, v in (("sun_revolutions", sun_revolutions), ("carrier_revolutions", carrier_revolutions),
                               ("planet_revolutions", planet_revolutions)) if v is not None}
    if len(given) != 1:
        raise InputError("run", sorted(given), "exactly one of sun_revolutions, carrier_revolutions, planet_revolutions")
    (key, v), = given.items()
    if not (isinstance(v, (int, float)) and 0 < v <= 200):
        raise InputError(f"run.{key}", v, "a number in (0, 200]")
    if not (isinstance(positions, int) and 1 <= positions <= 200000):
        raise InputError("run.positions", positions, "an integer in [1, 200000]")
    sun = {"sun_revolutions": v, "carrier_revolutions": v / train.ratio,
           "planet_revolutions": v / train.planet_ratio}[key]
    return start + 2 * math.pi * sun * np.arange(positions) / positions


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

    train: PlanetaryTrain
    options: IsostaticOptions
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
def _check_mobility(train: PlanetaryTrain) -> bool:
    """Raise for set-ups that cannot be simulated; True when the train is rigid and hyperstatic."""
    d = train.dof
    free = train.constraints.free_centres
    n = train.n_planets
    if d.singular:
        raise InputError(f"{free[-1]}_axis_free", True, f"false with the {free[0]} axis floating: two floating axes "
                         f"(case 3, {n} planets) are isostatic by count (section 3.2) but singular: translations of "
                         "any member change the planets' loop backlash as first harmonics of their angular positions, "
                         f"so the loop closures have rank {d.first_order_rank} < {1 + 2 * len(free)} and the floating "
                         "centres are not determined (see tca.dof)")
    if d.mobility == 0:
        return False
    if d.mobility > 0:
        raise InputError("planets.count", n, f"{d.isostatic_planets} for the chosen floating axes "
                         f"({', '.join(free) or 'none'}): with {n} planet(s) the train is under-constrained "
                         f"(N_f - N_c = {d.mobility}, section 3.2), so the floating centres are not determined")
    if free:
        raise InputError("planets.count", n, f"{d.isostatic_planets} when the {' and '.join(free)} axis floats: "
                         f"with {n} planets the train is hyperstatic (N_f - N_c = {d.mobility}, section 3.2) and "
                         "a floating member cannot satisfy all tangencies; fix the axes or change the planet count")
    return True


def _where_pos(phi1, pos, n):
    return lambda j: f"phi1 = {math.degrees(phi1[pos[j]]):.6f} deg (position {pos[j] + 1} of {n})"


def _nominal(train: PlanetaryTrain, fl: TrainFlanks, m: Members):
    """Tooth indices and guesses x = (u1, u2s, u2r, u3, phi2, phic) from the nominal motion."""
    N1, N2 = train.sun.teeth, train.planet.teeth
    phc = train.ratio * m.phi1
    ph2 = (N1 / N2) * (m.phi1 - phc - m.theta)
    P = poses(train, fl, m, ph2, phc)
    ks = nearest_tooth(m.phi1, 1, fl.sun.pitch_angle, N1, P.q)
    star = fl.sun.place(P.As, P.cs, ks, np.zeros(len(ks)))[0]
    kps = mate_tooth(train, fl.planet_s, P, "planet", P.Op, star)
    kpr = nearest_tooth(P.q + math.pi - P.a, -1, fl.planet_r.pitch_angle, N2, P.q)
    star = fl.planet_r.place(P.Ap, P.cp, kpr, np.zeros(len(ks)))[0]
    kr = mate_tooth(train, fl.ring, P, "ring", m.T[:, BODY_RING], star)
    m.teeth = np.stack([ks, kps, kpr, kr], -1)
    al = train.pressure_angle
    er = np.stack([np.cos(P.q), np.sin(P.q)], -1)
    Rq = rot2(P.q)
    I_s = m.T[:, BODY_SUN] + train.sun.r_p * er
    nu_s = apply(Rq, np.array([math.sin(al), math.cos(al)]))
    I_r = P.Tc + train.ring.r_p * er
    nu_r = apply(Rq, np.array([math.sin(al), -math.cos(al)]))
    us = line_crossing(fl.sun, P.As, P.cs, ks, I_s, nu_s)
    ups = line_crossing(fl.planet_s, P.Ap, P.cp, kps, I_s, nu_s)
    upr = line_crossing(fl.planet_r, P.Ap, P.cp, kpr, I_r, nu_r)
    ur = line_crossing(fl.ring, P.Ar, P.cr, kr, I_r, nu_r)
    return np.stack([us, ups, upr, ur, ph2, phc], -1)


def _inner(train, fl, m: Members, x0, opts, where):
    def fun(x, idx):
        return subtrain_eval(train, fl, m.take(idx), x)

    return newton(fun, x0, tol=opts.tol, maxiter=40, what="subtrain tangency (Eq. 3.18)", where=where)


def _set_free(m: Members, free, E, Np):
    for b_i, b in enumerate(free):
        m.T[:, _BODY[b]] = np.repeat(E[:, 2 * b_i:2 * b_i + 2], Np, 0)


def _solve_fictitious(train, fl, m, x, E, free, opts, wpos):
    """Eq. (3.18) per subtrain with its own carrier angle, Eq. (3.22) for the floating centres E (p, 2 n_free)."""
    Np = train.n_planets
    p = len(E)
    cols = [2 * _BODY[b] + c for b in free for c in (0, 1)]
    its = np.zeros(p, int)

    def wmem(i):
        return f"{wpos(i // Np)}, planet {i % Np + 1}"

    for it in range(opts.max_outer + 1):
        _set_free(m, free, E, Np)
        x = _inner(train, fl, m, x, opts, wmem).x
        if not free:
            break
        F, J = subtrain_eval(train, fl, m, x)
        dX = -np.linalg.solve(J, np.broadcast_to(JT_CENTRES[:, cols], (len(x), 6, len(cols))))
        dphc = dX[:, 5, :].reshape(p, Np, -1)
        phc = x[:, 5].reshape(p, Np)
        G = phc[:, :-1] - phc[:, 1:]
        err = np.abs(G).max(-1) * train.r_c
        todo = err >= opts.outer_tol
        if not todo.any():
            break
        bad = todo & (np.abs(E).max(-1) > 2.0)  # the floating centre ran away by more than 2 mm
        if it == opts.max_outer or bad.any():
            j = int(np.flatnonzero(bad)[0]) if bad.any() else int(np.argmax(err))
            raise ConvergenceError("fictitious unknowns (Eqs. 3.21-3.22)", wpos(j), float(err[j]), it)
        dG = dphc[:, :-1] - dphc[:, 1:]
        step = np.linalg.solve(dG[todo], -G[todo][..., None])[..., 0]
        E = E.copy()
        E[todo] += step
        its[todo] += 1
    return x, E, its


def _solve_direct(train, fl, m, x, E, free, opts, wpos):
    """All unknowns at once: centres E, one carrier angle, (u1, u2s, u2r, u3, phi2) per planet."""
    Np = train.n_planets
    p = len(E)
    nf = E.shape[1]
    cols = [2 * _BODY[b] + c for b in free for c in (0, 1)]
    X0 = np.concatenate([E, x[:, 5].reshape(p, Np).mean(1)[:, None], x[:, :5].reshape(p, 5 * Np)], 1)

    def split(X, idx):
        k = len(idx)
        mm = m.take((idx[:, None] * Np + np.arange(Np)).ravel())
        _set_free(mm, free, X[:, :nf], Np)
        x6 = np.concatenate([X[:, nf + 1:].reshape(k * Np, 5), np.repeat(X[:, nf], Np)[:, None]], 1)
        return mm, x6

    def fun(X, idx):
        k = len(idx)
        mm, x6 = split(X, idx)
        F, J = subtrain_eval(train, fl, mm, x6)
        F = F.reshape(k, Np, 6)
        J = J.reshape(k, Np, 6, 6)
        JJ = np.zeros((k, 6 * Np, X.shape[1]))
        for i in range(Np):
            r = slice(6 * i, 6 * i + 6)
            JJ[:, r, :nf] = JT_CENTRES[:, cols]
            JJ[:, r, nf] = J[:, i, :, 5]
            JJ[:, r, nf + 1 + 5 * i:nf + 6 + 5 * i] = J[:, i, :, :5]
        return F.reshape(k, 6 * Np), JJ

    r = newton(fun, X0, tol=opts.tol, maxiter=60, what="train tangency (direct solve of Eqs. 3.18 and 3.22)",
               where=wpos)
    X = r.x
    _, x6 = split(X, np.arange(p))
    _set_free(m, free, X[:, :nf], Np)
    return x6, X[:, :nf].copy(), r.iterations


def _switch(train, fl, m: Members, x, opts, wpos):
    """Backlash of the neighbouring pairs (Eqs. 3.19-3.20) and the new contacting pairs.

    Returns (teeth (M, 4), x guesses (M, 6), changed (M,), backlash (M, 2, 2)).
    """
    M = len(x)
    Np = train.n_planets
    F, J, P, mesh = subtrain_eval(train, fl, m, x, full=True)
    teeth = m.teeth.copy()
    xn = x.copy()
    changed = np.zeros(M, bool)
    backlash = np.full((M, 2, 2), np.nan)
    specs = (  # (mesh, flank a, pose a, tooth col a, u col a, flank b, pose b, body b, centre b, col b, u col b)
        (0, fl.sun, (P.As, P.cs), 0, 0, fl.planet_s, (P.Ap, P.cp), "planet", P.Op, 1, 1, mesh["point_s"], mesh["normal_s"]),
        (1, fl.planet_r, (P.Ap, P.cp), 2, 2, fl.ring, (P.Ar, P.cr), "ring", m.T[:, BODY_RING], 3, 3, mesh["point_r"],
         mesh["normal_r"]),
    )
    names = ("sun-planet", "planet-ring")
    for (k, fa, (Aa, ca), ta, ua_c, fb, (Ab, cb), body_b, Ob, tb, ub_c, c0, nu) in specs:
        ka = np.concatenate([m.teeth[:, ta] - 1, m.teeth[:, ta] + 1])
        A2a, c2a = np.concatenate([Aa, Aa]), np.concatenate([ca, ca])
        A2b, c2b = np.concatenate([Ab, Ab]), np.concatenate([cb, cb])
        P2 = _stack_poses(P)
        star = fa.place(A2a, c2a, ka, np.zeros(2 * M))[0]
        kb = mate_tooth(train, fb, P2, body_b, np.concatenate([Ob, Ob]), star)
        c02, nu2 = np.concatenate([c0, c0]), np.concatenate([nu, nu])
        ua0 = line_crossing(fa, A2a, c2a, ka, c02, nu2)
        ub0 = line_crossing(fb, A2b, c2b, kb, c02, nu2)
        ua, ub, s, ok, mg = backlash_solve(fa, A2a, c2a, ka, fb, A2b, c2b, kb, ua0, ub0, opts.tol)
        s = np.where(ok, s, np.nan).reshape(2, M).T  # (M, 2): previous, next
        mg = mg.reshape(2, M).T
        okk = ok.reshape(2, M).T
        backlash[:, k] = s
        cur_margin = mesh["margin"][:, k]
        S = np.stack([s[:, 0], np.zeros(M), s[:, 1]], -1)
        valid = np.stack([okk[:, 0] & (mg[:, 0] >= -opts.area_tol), cur_margin >= -opts.area_tol,
                          okk[:, 1] & (mg[:, 1] >= -opts.area_tol)], -1)
        marg = np.stack([mg[:, 0], cur_margin, mg[:, 1]], -1)
        Sv = np.where(valid, S, np.inf)
        smin = Sv.min(-1)
        none = ~np.isfinite(smin)
        if none.any():
            i = int(np.flatnonzero(none)[0])
            raise GeometryError(train.planet.name, "contact outside the working areas",
                                f"{wpos(i // Np)}, planet {i % Np + 1}, {names[k]} mesh: the contact point and those "
                                "of the neighbouring pairs leave the working areas (edge contact, not modelled by the "
                                "planar TCA)")
        # Neighbours whose common normal lies outside the working areas (or does not exist: extended profiles
        # past the base circle) are no candidates. The bounded teeth could still touch, but then an end of a
        # working area (tip or start of the fillet) enters the mate (the deepest point of two smooth profiles
        # is a common normal or an end point): that is edge contact, which the planar TCA does not model.
        inval = ~valid[:, [0, 2]]
        if inval.any():
            rows, cols = np.nonzero(inval)
            idx = rows + cols * M
            for fo, Ao, co, ko, fm_, Am, cm, km in ((fa, A2a, c2a, ka, fb, A2b, c2b, kb),
                                                    (fb, A2b, c2b, kb, fa, A2a, c2a, ka)):
                for ulim in (fo.u_form, fo.u_tip):
                    gap, _ = corner_gap(fo, Ao[idx], co[idx], ko[idx], np.full(len(idx), ulim), fm_, Am[idx],
                                        cm[idx], km[idx])
                    bad = gap < -opts.tie_tol
                    if bad.any():
                        i = int(rows[np.argmax(bad)])
                        where_end = "start of the fillet" if ulim == fo.u_form else "tip"
                        raise GeometryError(train.planet.name, "edge contact",
                                            f"{wpos(i // Np)}, planet {i % Np + 1}, {names[k]} mesh: the {where_end} of "
                                            f"the {fo.gear.name}'s flank of a neighbouring pair enters the mate by "
                                            f"{-gap[bad].min() * 1e3:.3f} um (edge contact, not modelled by the planar "
                                            "TCA)")
        tie = valid & (S <= smin[:, None] + opts.tie_tol)
        choice = np.argmax(np.where(tie, marg, -np.inf), -1)
        edge = ~valid[:, 1] & (choice != 1) & (S[np.arange(M), choice] > opts.tie_tol)
        if edge.any():
            i = int(np.flatnonzero(edge)[0])
            raise GeometryError(train.planet.name, "edge contact",
                                f"{wpos(i // Np)}, planet {i % Np + 1}, {names[k]} mesh: the contact leaves the "
                                f"working areas while the next pair still has {S[i, choice[i]] * 1e3:.3f} um backlash "
                                "(tip edge contact, not modelled by the planar TCA)")
        for d, col in ((0, 0), (2, 1)):
            sel = choice == d
            if sel.any():
                idx = np.flatnonzero(sel) + col * M
                rows = np.flatnonzero(sel)
                teeth[rows, ta] = ka[idx]
                teeth[rows, tb] = kb[idx]
                xn[rows, ua_c] = ua[idx]
                xn[rows, ub_c] = ub[idx]
                changed[rows] = True
    return teeth, xn, changed, backlash


def _stack_poses(P: Poses) -> Poses:
    """The poses twice over (for the two neighbours of every member)."""
    return Poses(*(np.concatenate([getattr(P, f), getattr(P, f)]) for f in
                   ("As", "cs", "Ap", "cp", "Op", "Tc", "Ar", "cr", "q", "a")))


def run_isostatic_tca(train: PlanetaryTrain, phi1, options: IsostaticOptions = IsostaticOptions()) -> IsostaticResult:
    """Configuration of the train (centres, carrier, planets, contacting teeth) at the sun angles phi1 [rad]."""
    t0 = time.perf_counter()
    rigid = _check_mobility(train)
    phi1 = np.asarray(phi1, float).reshape(-1)
    if len(phi1) == 0 or not np.all(np.isfinite(phi1)):
        raise InputError("phi1", phi1[:5].tolist(), "one or more finite sun angles")
    fl = TrainFlanks.of(train, options.section_z)
    n, Np = len(phi1), train.n_planets
    free = train.constraints.free_centres
    if options.method == "direct" and rigid and Np > 1:
        raise InputError("solver.method", "direct", "'fictitious' for a rigid hyperstatic train (no simultaneous "
                         "tangency of all planets exists)")
    # members: position-major, planet-minor
    T = np.zeros((n * Np, 3, 2))
    T[:, BODY_SUN] = train.sun_center
    T[:, BODY_CARRIER] = train.carrier_center
    T[:, BODY_RING] = train.ring_center
    runout_p = np.array([p.tooth_transform(np.array(0))[1][:2] for p in train.planets])
    m = Members(np.repeat(phi1, Np), np.tile(train.theta, n), np.tile(train.pins, (n, 1)), np.tile(runout_p, (n, 1)),
                np.zeros((n * Np, 4), int), T)
    x = _nominal(train, fl, m)
    E = np.zeros((n, 2 * len(free)))
    outer_its = np.zeros(n, int)
    backlash = np.full((n * Np, 2, 2), np.nan)
    pos = np.arange(n)
    rounds = 0
    for rounds in range(1, options.max_rounds + 1):
        mem = (pos[:, None] * Np + np.arange(Np)).ravel()
        mm = m.take(mem)
        wpos = _where_pos(phi1, pos, n)
        if options.method == "direct" and free:
            xs, Es, its = _solve_direct(train, fl, mm, x[mem], E[pos], free, options, wpos)
        else:
            xs, Es, its = _solve_fictitious(train, fl, mm, x[mem], E[pos], free, options, wpos)
        x[mem], E[pos] = xs, Es
        outer_its[pos] += its
        m.T[mem] = mm.T
        teeth, xn, changed, bl = _switch(train, fl, mm, xs, options, wpos)
        backlash[mem] = bl
        ch_pos = changed.reshape(-1, Np).any(-1)
        if not ch_pos.any():
            break
        m.teeth[mem] = teeth
        x[mem] = xn
        pos = pos[ch_pos]
    else:
        raise ConvergenceError("contact switching (Eqs. 3.19-3.20)", _where_pos(phi1, pos, n)(0), 0.0, rounds)

    F, J, P, mesh = subtrain_eval(train, fl, m, x, full=True)
    res = np.abs(F).max(-1).reshape(n, Np).max(-1)
    if np.any(res > 10 * options.tol):
        j = int(np.argmax(res))
        raise ConvergenceError("train TCA verification", _where_pos(phi1, np.arange(n), n)(j), float(res[j]), 0)
    phc_i = x[:, 5].reshape(n, Np)
    if rigid:
        phc = phc_i.max(-1)
        planet_bl = (phc[:, None] - phc_i) * train.sun.r_b / train.ratio
    else:
        phc = phc_i.mean(-1)
        planet_bl = np.zeros((n, Np))
    Nt = np.array([train.sun.teeth, train.planet.teeth, train.planet.teeth, train.ring.teeth])
    return IsostaticResult(
        train=train, options=options, phi1=phi1, phi_c=phc, phi_c_planets=phc_i, te=phc - train.ratio * phi1,
        sun_center=m.T[::Np, BODY_SUN].copy(), carrier_center=m.T[::Np, BODY_CARRIER].copy(),
        ring_center=m.T[::Np, BODY_RING].copy(), phi2=x[:, 4].reshape(n, Np),
        teeth=np.mod(m.teeth, Nt).reshape(n, Np, 4), params=x[:, :4].reshape(n, Np, 4),
        point_s=mesh["point_s"].reshape(n, Np, 2), point_r=mesh["point_r"].reshape(n, Np, 2),
        margin=mesh["margin"].reshape(n, Np, 2), backlash=backlash.reshape(n, Np, 2, 2), planet_backlash=planet_bl,
        residual=res, outer_iterations=outer_its, rounds=rounds, rigid=rigid, dof=train.dof,
        elapsed=time.perf_counter() - t0,
    )
