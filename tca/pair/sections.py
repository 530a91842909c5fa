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
    def g(y, idx):
        x = np.insert(y, 1, s, axis=-1)
        F, J = fun(x, np.zeros(len(y), int))
        return F[:, :4], J[:, :4][:, :, _Y]

    r = newton(g, y0[None], NewtonOptions(tol=tol, maxiter=30, max_backtracks=10), raise_on_failure=False)
    if not r.converged[0]:
        return None
    x = np.insert(r.x[0], 1, s)
    F, J = fun(x[None], np.zeros(1, int))
    return x, F[0], J[0]


def _slope(J: np.ndarray) -> tuple[float, np.ndarray]:
    """dh/ds and dy/ds at a solution of (S1) (S2)."""
    A = J[:4][:, _Y]
    dy = -np.linalg.solve(A, J[:4, 1])
    return float(J[4, 1] + J[4, _Y] @ dy), dy


def section_tangency(f1: PlacedFlank, f2: PlacedFlank, phi1: float, x0: np.ndarray, tol: float,
                     centre: tuple[float, float], maxiter: int = 60):
    """Point of tangency (u1, v1, u2, v2, phi2) at phi1 [rad] from the guess x0, by sections (module docstring);
    ``centre`` (u_c, v_c) [mm] selects the point of a line contact. Returns (x, residual) or None."""
    fun = tangency_system(f1, f2, np.array([float(phi1)]))
    v_lo, v_hi = f1.surface.v_range
    s = float(np.clip(x0[1] if np.isfinite(x0[1]) else centre[1], v_lo, v_hi))
    y = np.asarray(x0, float)[_Y]
    sol = _inner(fun, s, y, tol)
    if sol is None:
        s = float(np.clip(centre[1], v_lo, v_hi))
        sol = _inner(fun, s, y, tol)
        if sol is None:
            return None
    x, F, J = sol
    bracket = [None, None]  # (s, h) with h < 0 and h > 0
    for _ in range(maxiter):
        h = float(F[4])
        if abs(h) < tol:
            return _prefer(fun, x, F, J, tol, centre, (v_lo, v_hi))
        bracket[0 if h < 0 else 1] = (s, h)
        dh, _ = _slope(J)
        step = -h / dh if dh != 0 and math.isfinite(dh) else math.inf
        s_new = s + step
        if bracket[0] is not None and bracket[1] is not None:
            a, b = sorted((bracket[0][0], bracket[1][0]))
            if not a < s_new < b:
                s_new = 0.5 * (a + b)
        else:
            limit = 0.25 * (v_hi - v_lo)
            if not math.isfinite(s_new) or abs(s_new - s) > limit:
                s_new = s + math.copysign(limit, step if math.isfinite(step) else -h)
            s_new = float(np.clip(s_new, v_lo, v_hi))
            if s_new == s:
                return None  # the root lies beyond the surface: no tangency at this position
        sol = _inner(fun, s_new, x[_Y], tol)
        if sol is None:
            if bracket[0] is not None and bracket[1] is not None:
                return None
            return None
        s = s_new
        x, F, J = sol
    return None


def _prefer(fun, x, F, J, tol, centre, v_range):
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
