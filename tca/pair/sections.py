r"""Tangency of nearly conjugate flanks, solved section by section (the fallback of the pair TCA's Newton solve).

Aligned involute helical gears touch along a line, and a light crowning (a few micrometres over the face)
turns that line into a point whose position along the line is fixed by a curvature difference four to
six orders of magnitude below the others. The 5x5 Jacobian of the tangency system
(:func:`tca.contact.systems.tangency_system`, unknowns :math:`x = (u_1, v_1, u_2, v_2, \phi_2)`) then has
one singular value near zero: a Newton step along that direction is as long as the residual's component
on it divided by that singular value, and the curvature of the contact line in the parameters spoils
it (seen: a helical 19/24 pair at 30 deg whose iterates ran 40 mm along the line off the face; a
crowned helical 23/67 pair stalling at a residual of 1e-5 mm).

Here the nearly free direction is taken out of the Newton solve. The axial position on flank 1,
:math:`s = v_1`, is held fixed (every contact line crosses the sections :math:`v_1 = s` at an angle:
it runs along the face on spur gears and at the base helix angle on helical ones), and the other four
unknowns :math:`y = (u_1, u_2, v_2, \phi_2)` solve the well-conditioned system of the three position
equations and the tangency across the profile,

.. math::  G(y; s) = \big(r_f^{(1)} - r_f^{(2)},\ n_f^{(1)}\cdot r^{(2)}_{f,u}\big) = 0 .        (S1)

The last equation of the tangency system becomes a function of the section alone,

.. math::  h(s) = n_f^{(1)}\cdot r^{(2)}_{f,v}\big|_{y(s)},\qquad
   \frac{dh}{ds} = J_{5,v_1} - J_{5,y}\,J_{G,y}^{-1} J_{G,v_1}                                    (S2)

(the Schur complement of the 5x5 Jacobian :math:`J`), and the contact is its root, found by Newton
on :math:`s` with bisection once a sign change brackets it. On exactly conjugate flanks (line
contact) :math:`h \equiv 0`; then the point of the line nearest the centre of flank 1's working area
:math:`(u_c, v_c)` is taken, by Newton on :math:`(u_1(s) - u_c)^2 + (s - v_c)^2` with
:math:`du_1/ds` from (S2)'s solve (the same choice the Newton solve makes with its preferred point).
"""

from __future__ import annotations

import math

import numpy as np

from tca.contact.systems import PlacedFlank, tangency_system
from tca.numerics.newton import NewtonOptions, newton

__all__ = ["section_tangency"]

_Y = np.array([0, 2, 3, 4])  # unknowns of (S1): u1, u2, v2, phi2


def _inner(fun, s: float, y0: np.ndarray, tol: float):
    """y(s) of (S1) by Newton from y0; (x, F, J) at the solution or None."""
    x, F, J, ok = _sections(fun, np.array([float(s)]), np.asarray(y0, float)[None], tol)
    return (x[0], F[0], J[0]) if ok[0] else None


def _slope(J: np.ndarray) -> tuple[float, np.ndarray]:
    """dh/ds and dy/ds at a solution of (S1) (S2)."""
    A = J[:4][:, _Y]
    dy = -np.linalg.solve(A, J[:4, 1])
    return float(J[4, 1] + J[4, _Y] @ dy), dy


def section_tangency(f1: PlacedFlank, f2: PlacedFlank, phi1: float, x0: np.ndarray, tol: float,
                     centre: tuple[float, float], maxiter: int = 20):
    """Point of tangency (u1, v1, u2, v2, phi2) at phi1 [rad] from the guess x0, by sections (module docstring);
    ``centre`` (u_c, v_c) [mm] selects the point of a line contact. Returns (x, residual) or None.

    Newton on the section from the guess first; where it finds no root (no sign change of h within reach, as
    on a flank whose tip relief breaks the contact line at its kink), the sections across the surface are
    scanned and the root (or the part of a line contact) nearest the guess's section is taken."""
    fun = tangency_system(f1, f2, np.array([float(phi1)]))
    v_range = f1.surface.v_range
    s0 = float(np.clip(x0[1] if np.isfinite(x0[1]) else centre[1], *v_range))
    sol = _inner(fun, s0, np.asarray(x0, float)[_Y], tol)
    if sol is not None:
        found = _newton_on_sections(fun, sol, tol, v_range, maxiter)
        if found is not None:
            return _prefer(fun, *found, tol, centre, v_range)
    return _scan(fun, s0, np.asarray(x0, float)[_Y], tol, centre, v_range)


def _newton_on_sections(fun, sol, tol, v_range, maxiter):
    """Newton on s with bisection once bracketed (S2); (x, F, J) of a root or None."""
    v_lo, v_hi = v_range
    x, F, J = sol
    s = float(x[1])
    bracket = [None, None]  # sections with h < 0 and h > 0
    for _ in range(maxiter):
        h = float(F[4])
        if abs(h) < tol:
            return x, F, J
        bracket[0 if h < 0 else 1] = s
        dh, _ = _slope(J)
        s_new = s - h / dh if dh != 0 else math.nan
        if bracket[0] is not None and bracket[1] is not None:
            a, b = sorted(bracket)
            if not (math.isfinite(s_new) and a < s_new < b):
                s_new = 0.5 * (a + b)
        elif not (math.isfinite(s_new) and abs(s_new - s) <= 0.25 * (v_hi - v_lo) and v_lo <= s_new <= v_hi):
            return None  # no root within reach of Newton: the scan takes over
        nxt = _inner(fun, s_new, x[_Y], tol)
        if nxt is None:
            return None
        s = s_new
        x, F, J = nxt
    return None


SCAN_SECTIONS = 41  # sections across the surface's axial range scanned when Newton on the section fails


def _sections(fun, ss: np.ndarray, Y0: np.ndarray, tol: float):
    """y(s) of (S1) at every section ss (k,) from the starts Y0 (k, 4), in one batched Newton solve (each member
    iterates on its own, as :func:`_inner` would); (x (k, 5), F, J, converged (k,))."""
    zeros = np.zeros(len(ss), int)

    def g(y, idx):
        x = np.insert(y, 1, ss[idx], axis=-1)
        F, J = fun(x, zeros[: len(y)])
        return F[:, :4], J[:, :4][:, :, _Y]

    r = newton(g, Y0, NewtonOptions(tol=tol, maxiter=30, max_backtracks=10), raise_on_failure=False)
    x = np.insert(r.x, 1, ss, axis=-1)
    F, J = fun(x, zeros)
    return x, F, J, r.converged


def _scan(fun, s0: float, y0: np.ndarray, tol: float, centre, v_range):
    """Roots of h over sections across v_range (a sign change bisected, or |h| < tol); the one nearest s0.

    Every section is solved from the guess first (one batched solve); a section that fails is retried from
    its nearest solved neighbour, in waves, until a wave solves no further section."""
    ss = np.linspace(*v_range, SCAN_SECTIONS)
    x, F, J, ok = _sections(fun, ss, np.repeat(np.asarray(y0, float)[None], len(ss), 0), tol)
    while ok.any() and not ok.all():
        solved = np.flatnonzero(ok)
        todo = np.flatnonzero(~ok)
        near = solved[np.argmin(np.abs(solved[None, :] - todo[:, None]), axis=1)]
        xt, Ft, Jt, okt = _sections(fun, ss[todo], x[near][:, _Y], tol)
        if not okt.any():
            break
        t = todo[okt]
        x[t], F[t], J[t], ok[t] = xt[okt], Ft[okt], Jt[okt], True
    sols = {int(i): (x[i], F[i], J[i]) for i in np.flatnonzero(ok)}
    roots = []
    for i in sorted(sols):
        xi, Fi, Ji = sols[i]
        if abs(Fi[4]) < tol:
            roots.append((abs(ss[i] - s0), sols[i]))
        j = i + 1
        if j in sols and Fi[4] * sols[j][1][4] < 0:
            r = _bisect(fun, sols[i], sols[j], tol)
            if r is not None:
                roots.append((abs(r[0][1] - s0), r))
    if not roots:
        return None
    x, F, J = min(roots, key=lambda q: q[0])[1]
    return _prefer(fun, x, F, J, tol, centre, v_range)


BISECT_STEPS = 24  # a root of a smooth h is found in 5-10 steps (measured over the TCA tests); a bracket that
# takes longer is a jump of h between two branches of (S1), not a root: it is given up


def _bisect(fun, a, b, tol, maxiter: int = BISECT_STEPS):
    """A root of h between two sections of opposite sign (secant steps kept inside the bracket, a bisection every
    third step)."""
    (xa, Fa, _), (xb, Fb, _) = a, b
    for _ in range(maxiter):
        sa, sb, ha, hb = float(xa[1]), float(xb[1]), float(Fa[4]), float(Fb[4])
        s = sa - ha * (sb - sa) / (hb - ha)
        if not (min(sa, sb) < s < max(sa, sb)) or _ % 3 == 2:
            s = 0.5 * (sa + sb)
        r = _inner(fun, s, 0.5 * (xa[_Y] + xb[_Y]), tol)
        if r is None:
            return None
        if abs(r[1][4]) < tol:
            return r
        if r[1][4] * ha < 0:
            xb, Fb = r[0], r[1]
        else:
            xa, Fa = r[0], r[1]
        if abs(sb - sa) < 1e-12:
            return None
    return None


def _prefer(fun, x, F, J, tol, centre, v_range):  # noqa: PLR0913
    """A solution; on a line contact (h = 0 along the line) the point nearest the centre of flank 1's area."""
    dh, dy = _slope(J)
    u_c, v_c = centre
    for _ in range(4):
        du = dy[0]
        s = float(x[1])
        t = ((u_c - x[0]) * du + (v_c - s)) / (du * du + 1.0)
        if abs(t) < 1e-9:
            break
        s_new = float(np.clip(s + t, *v_range))
        sol = _inner(fun, s_new, x[_Y] + dy * (s_new - s), tol)
        if sol is None or abs(sol[1][4]) >= tol:
            break  # not a line contact (or not along it): keep the root found
        x, F, J = sol
        dh, dy = _slope(J)
    return x, float(np.abs(F).max())
