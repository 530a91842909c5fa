r"""Multi-body TCA of a planar planetary train with floating members (section 3.3, Eqs. 3.18–3.23).

For every given sun angle :math:`\phi_1` the configuration of the whole train is found:

1. **Tooth numbering** (Fig. 3.2). Each mesh (sun–planet *i*, planet *i*–ring) has a pair of tooth
   indices. The first guess takes the teeth whose flanks' pitch points are nearest the mesh's
   pitch point in the nominal motion; points of contact are first guessed where the flanks cross
   the nominal line of action.
2. **Fictitious unknowns** (section 3.3.3). Each subtrain *i* gets its own carrier angle
   :math:`\phi_c^{(i)}`, and Eq. (3.18) (planar form, :mod:`tca.isostatic.subtrain`) is solved for the
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
   absolute (from the zero-backlash reference of :mod:`tca.isostatic.train`).

The train must be isostatic when a member floats (:mod:`tca.isostatic.dof`). A hyperstatic train with all
axes fixed (e.g. case 1 constraints with 3 planets) is solved as a rigid train: the carrier takes
the largest :math:`\phi_c^{(i)}` (the first planet to touch) and the others keep a backlash.

Every Newton solve raises a :class:`~tca.errors.ConvergenceError` naming the position when it fails;
contact leaving the working areas (edge contact, not modelled in the plane) raises a
:class:`~tca.errors.GeometryError` naming the position and the mesh.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import numpy as np

from tca.errors import ConvergenceError, InputError
from tca.isostatic.flanks import TrainFlanks, apply, nearest_tooth, rot2
from tca.isostatic.subtrain import (BODY_CARRIER, BODY_RING, BODY_SUN, JT_CENTRES, Members, line_crossing,
                             mate_tooth, poses, subtrain_eval)
from tca.isostatic.result import ARCSEC, IsostaticResult, dominant_period, fit_circle  # noqa: F401  (re-exported)
from tca.isostatic.switching import switch_pairs
from tca.isostatic.train import IsostaticTrain
from tca.numerics.newton import NewtonOptions, newton

__all__ = ["IsostaticOptions", "phi1_grid", "check_mobility", "scaled_tolerances", "ROUNDING_FACTOR",
           "run_isostatic_tca", "ARCSEC", "IsostaticResult", "dominant_period", "fit_circle"]

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


def phi1_grid(train: IsostaticTrain, positions: int, *, sun_revolutions: float | None = None,
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


def check_mobility(train: IsostaticTrain) -> bool:
    """Raise for set-ups that cannot be simulated; True when the train is rigid and hyperstatic."""
    d = train.dof
    free = train.constraints.free_centres
    n = train.n_planets
    if d.singular:
        raise InputError(f"{free[-1]}_axis_free", True, f"false with the {free[0]} axis floating: two floating axes "
                         f"(case 3, {n} planets) are isostatic by count (section 3.2) but singular: translations of "
                         "any member change the planets' loop backlash as first harmonics of their angular positions, "
                         f"so the loop closures have rank {d.first_order_rank} < {1 + 2 * len(free)} and the floating "
                         "centres are not determined (see tca.isostatic.dof)")
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


def _nominal(train: IsostaticTrain, fl: TrainFlanks, m: Members):
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

    return newton(fun, x0, NewtonOptions(tol=opts.tol, maxiter=40), what="subtrain tangency (Eq. 3.18)", where=where)


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

    r = newton(fun, X0, NewtonOptions(tol=opts.tol, maxiter=60),
               what="train tangency (direct solve of Eqs. 3.18 and 3.22)", where=wpos)
    X = r.x
    _, x6 = split(X, np.arange(p))
    _set_free(m, free, X[:, :nf], Np)
    return x6, X[:, :nf].copy(), r.iterations


ROUNDING_FACTOR = 16.0  # residual terms summed in Eq. (3.18), each rounded to eps |angle| R


def scaled_tolerances(train: IsostaticTrain, phi1: np.ndarray, options: IsostaticOptions) -> IsostaticOptions:
    r"""Newton targets no finer than double precision can resolve at the angles reached [mm].

    Positions are :math:`R(\phi)\,r` with angles that grow without bound over a long run; rounding
    gives each an error of about :math:`\varepsilon\,|\phi|\,R` (:math:`\varepsilon` the machine
    epsilon, :math:`R` the ring's tip-to-root size), so after 50 carrier revolutions (sun angle
    ~ 900 rad, planet angle larger by :math:`N_1/N_2`) the residuals of Eq. (3.18) cannot go below
    ~ 1e-11 mm. The targets ``tol`` and ``outer_tol`` are raised to
    :math:`16\,\varepsilon\,\Phi\,R` (and ten times that), :math:`\Phi` the largest member angle
    [rad]; for the short runs of the report they are unchanged.
    """
    phi_max = float(np.max(np.abs(phi1))) * max(1.0, train.sun.teeth / train.planet.teeth)
    size = train.ring.r_p + 3 * train.ring.module
    floor = float(ROUNDING_FACTOR * np.finfo(float).eps * phi_max * size)
    if floor <= options.tol:
        return options
    return dataclasses.replace(options, tol=max(options.tol, floor), outer_tol=max(options.outer_tol, 10 * floor))


def run_isostatic_tca(train: IsostaticTrain, phi1, options: IsostaticOptions = IsostaticOptions()) -> IsostaticResult:
    """Configuration of the train (centres, carrier, planets, contacting teeth) at the sun angles phi1 [rad]."""
    t0 = time.perf_counter()
    rigid = check_mobility(train)
    phi1 = np.asarray(phi1, float).reshape(-1)
    if len(phi1) == 0 or not np.all(np.isfinite(phi1)):
        raise InputError("phi1", phi1[:5].tolist(), "one or more finite sun angles")
    options = scaled_tolerances(train, phi1, options)
    fl = train.flanks(options.section_z)
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
        teeth, xn, changed, bl = switch_pairs(train, fl, mm, xs, options, wpos)
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
