r"""TCA of a helical pinion meshing with a face gear: one sub-gear drive of the inverted train of Part 2.

Frames. The meshing frame is the generation frame :math:`S_m` of :mod:`tca.face.face_gear`: the face gear
sits at its generating position, and the pinion replaces the shaper with its axis parallel to the
shaper's, its pitch cylinder touching the shaper's pitch cylinder internally along the pitch line
through P (Ref. 1 of Part 2): pinion centre :math:`(r_{ps} - r_{pp}, 0, 0)`, its reference tooth
centred on +x (toward P) at :math:`\phi_p = 0`; the face gear at :math:`\phi_2 = 0` has a tooth
space centred on P. The pinion axis meets the face-gear axis at the *apex* :math:`C_p`, at distance

.. math:: d = \frac{L_p + r_{pp}\cos\gamma}{\sin\gamma}

from the pitch point along the pinion axis (the pinion's pitch point lies on the axode of the
pinion/face-gear pair).

Contact (Eqs. 2.5–2.6 and 2.9–2.10): position and normal equality of the two flanks, solved with
:func:`tca.contact.systems.tangency_system` (five equations in :math:`u_1, v_1, u_2, v_2, \phi_{driven}` for a
given :math:`\phi_{driver}`) and the batched :func:`tca.numerics.newton.newton`. The driving member turns
positively; a driving pinion pushes with its +y flank on the face gear's -y flank (tooth 0); a
driving face gear pushes with the +y flank of its tooth -1 on the pinion's -y flank (the pair that
faces across the tooth space centred on P).

Pairs of teeth. The reference pair gives :math:`\phi_{dn} = G(\phi_{dr})`; the pair *j* pitches later
(:math:`j = +1` the report's *backward* pair, :math:`j = -1` the *forward* pair) gives
:math:`G(\phi_{dr} - jT_{dr}) + jT_{dn}`, :math:`T = 2\pi/N`. The transition angles are the
positions of simultaneous contact of two neighbouring pairs (Eqs. 2.7–2.8 and 2.11–2.12):
:math:`G(\phi_{min}) = G(\phi_{min} + T_{dr}) - T_{dn}` (current and forward pair) and
:math:`G(\phi_{max}) = G(\phi_{max} - T_{dr}) + T_{dn}` (current and backward pair) — each evaluation
of G an exact Newton solve, the root found by Brent's method; identical teeth give
:math:`\phi_{max} = \phi_{min} + T_{dr}` (checked). The reference pair is in contact on
:math:`[\phi_{min}, \phi_{max}]`.

Bounded surfaces. Where the point of tangency leaves a working area across the face width (face
gear: radius :math:`L_1` or :math:`L_2`; pinion: :math:`z_{min}`, :math:`z_{max}`), the flanks touch
along that boundary instead (edge contact): :math:`r_1 = r_2`, :math:`c(u_e, v_e) = 0` and the boundary
curve tangent to the other flank, :math:`n_o\cdot(c_v r_u - c_u r_v)_e = 0` (as in :mod:`tca.contact.systems`,
with a finite-difference Jacobian). A tangency point beyond a tip or root boundary ends the pair's
contact (edge contact across the profile is not modelled; an error names it if it happens inside
:math:`[\phi_{min}, \phi_{max}]`). Transmission errors of the sub-drive (Fig. 2.3):
:math:`\Delta\phi_{dn} = \phi_{dn} - (N_{dr}/N_{dn})\phi_{dr}` [rad], absolute from the symmetric
configuration.
"""

from __future__ import annotations

from tca.units import ARCSEC

import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

from tca.contact.systems import PlacedFlank, tangency_system
from tca.contact.ellipse import contact_ellipse
from tca.errors import ConvergenceError, GeometryError, InputError
from tca.face.face_gear import FaceGear
from tca.geometry.gear import Gear
from tca.numerics.newton import NewtonOptions, NewtonResult, PreferredPoint, newton
from tca.numerics.transforms import Mount

__all__ = ["FaceMesh", "FaceMeshResult", "ReferenceTrace", "run_face_mesh", "trace_reference_pair", "ARCSEC", "SURFACE",
           "EDGE"]

PREFER_WEIGHTS = np.array([1e-3, 1e-3, 0.0, 0.0, 0.0])


@dataclass(frozen=True)
class FaceMesh:
    """A pinion meshing with a face gear, carrier at rest; `driver` is 'pinion' or 'face'."""

    face: FaceGear
    pinion: Gear
    driver: str = "pinion"
    pinion_offset: float | None = None  # middle of the pinion's face width from the pitch point, along its axis [mm]

    def __post_init__(self):
        p, s = self.pinion, self.face.shaper
        if self.driver not in ("pinion", "face"):
            raise InputError("driver", self.driver, "'pinion' or 'face'")
        if p.internal:
            raise InputError(f"{p.name}.internal", True, "an external pinion")
        for key, a, b in (("module_mm", p.module, s.module), ("pressure_angle_deg", p.pressure_angle, s.pressure_angle),
                          ("reference_helix_deg", p.beta_ref, s.beta_ref)):
            if abs(a - b) > 1e-12:
                raise InputError(f"{p.name}.{key}", a if key == "module_mm" else math.degrees(a),
                                 f"equal to the shaper's {b if key == 'module_mm' else math.degrees(b)} (the shaper "
                                 f"imitates the pinion)")
        if p.helix > 0 and p.hand != s.hand:
            raise InputError(f"{p.name}.hand", "right" if p.hand > 0 else "left",
                             "the hand of the shaper (the shaper imitates the pinion)")
        if abs(p.helix - s.helix) > 1e-12:
            raise InputError(f"{p.name}.helix_deg", math.degrees(p.helix), f"the shaper's {math.degrees(s.helix)}")
        if p.teeth > s.teeth:
            raise InputError(f"{p.name}.teeth", p.teeth, f"<= shaper teeth {s.teeth} (N_s > N_p localizes the contact; "
                             f"N_s = N_p gives line contact)")

    @property
    def ratio(self) -> float:
        """dphi_driven/dphi_driver of the ideal drive."""
        np_, nf = self.pinion.teeth, self.face.teeth
        return np_ / nf if self.driver == "pinion" else nf / np_

    @property
    def pitches(self) -> tuple[float, float]:
        """Angular pitches (T_driver, T_driven) [rad]."""
        tp, tf = self.pinion.pitch_angle, self.face.pitch_angle
        return (tp, tf) if self.driver == "pinion" else (tf, tp)

    @property
    def offset(self) -> float:
        """Middle of the pinion's face width from the pitch point [mm]: given, or the middle of the
        face-gear width (L1 + L2)/2 carried along the pitch line, ((L1 + L2)/2 - L_p)/sin(gamma)."""
        if self.pinion_offset is not None:
            return self.pinion_offset
        f = self.face
        return (0.5 * (f.L1 + f.L2) - f.pitch_radius) / math.sin(f.shaft_angle)

    def mounts(self) -> tuple[Mount, Mount]:
        """(pinion mount, face-gear mount) in the meshing frame S_m.

        The pinion's angle is that of its tooth centre in the transverse section through the pitch
        point P (mount phase k e for the face-width offset e), so phi = 0 is the symmetric position."""
        e = self.offset
        mp = Mount(np.array([self.face.shaper.r_p - self.pinion.r_p, 0.0, e]), np.eye(3), self.pinion.k_screw * e)
        return mp, self.face.mount()

    def flanks(self) -> tuple[PlacedFlank, PlacedFlank]:
        """(driver flank, driven flank) of the reference pair."""
        mp, mf = self.mounts()
        if self.driver == "pinion":
            return PlacedFlank(self.pinion, 1, mp), PlacedFlank(self.face, -1, mf, tooth=0)
        return PlacedFlank(self.face, 1, mf, tooth=-1), PlacedFlank(self.pinion, -1, mp)

    @property
    def apex_distance(self) -> float:
        """d: from the pinion's apex (its axis meeting the face-gear axis) to its pitch point [mm]."""
        C, B = self.face.frame
        a2 = -B[:, 2]
        x0 = self.face.shaper.r_p - self.pinion.r_p
        s = (x0 - C[0]) / a2[0]
        return -(C[2] + s * a2[2])

    def start_angle(self) -> float:
        """Driver angle at which the flank of the reference pair passes the pitch point (z = 0)."""
        a = math.pi / (2 * self.pinion.teeth)
        return -a if self.driver == "pinion" else a * self.pinion.teeth / self.face.teeth


# ------------------------------------------------------------------------------------ bounded contact
SURFACE, EDGE = 1, 2  # kinds of contact (as tca.pair.analysis.ContactKind)
_LONGITUDINAL = (2, 3)  # working-area boundaries across the face width: face gear L2, L1; pinion z_max, z_min
_FD_STEP = np.array([1e-6, 1e-6, 1e-6, 1e-6, 1e-8])


def _boundary(flank: PlacedFlank, loc, b: int):
    """Value and derivatives (c, c_u, c_v) of longitudinal boundary b of a flank (<= 0 inside) [mm]."""
    g = flank.gear
    if isinstance(g, FaceGear):
        rho = np.hypot(loc.r[..., 0], loc.r[..., 1])
        du = (loc.r[..., 0] * loc.r_u[..., 0] + loc.r[..., 1] * loc.r_u[..., 1]) / rho
        dv = (loc.r[..., 0] * loc.r_v[..., 0] + loc.r[..., 1] * loc.r_v[..., 1]) / rho
        return (rho - g.L2, du, dv) if b == 2 else (g.L1 - rho, -du, -dv)
    ar = g.area(flank.side)
    z, zu, zv = loc.r[..., 2], loc.r_u[..., 2], loc.r_v[..., 2]
    return (z - ar.z_max, zu, zv) if b == 2 else (ar.z_min - z, -zu, -zv)


class _Contacts:
    """Contact of the reference pair at given driver angles: tangency inside both working areas, or
    contact of a face-width boundary of one flank with the other flank (edge contact)."""

    def __init__(self, mesh: FaceMesh, area_tol: float):
        self.mesh, self.area_tol = mesh, area_tol
        self.f1, self.f2 = mesh.flanks()
        self.prefer = _prefer(self.f1)

    def constraints(self, x) -> np.ndarray:
        """(n, 2, 5) working-area constraints of both flanks (pinion padded with -inf)."""
        out = np.full((len(x), 2, 5), -np.inf)
        for i, (f, k) in enumerate(((self.f1, 0), (self.f2, 2))):
            c = f.constraints(f.surface.evaluate(x[:, k], x[:, k + 1]), x[:, k])
            out[:, i, :c.shape[-1]] = c
        return out

    def tangency(self, phis, guess):
        return _newton(self.f1, self.f2, phis, guess)

    def edge(self, phis, guess, e: int, b: int):
        """Boundary b of flank e (1 driver, 2 driven) touching the other flank: five equations
        r1 = r2, c(u_e, v_e) = 0, n_other . (c_v r_u - c_u r_v)_e = 0 (FD Jacobian)."""
        f1, f2 = self.f1, self.f2
        fe = f1 if e == 1 else f2

        def res(x, idx):
            w1, l1, _ = f1.world(x[:, 0], x[:, 1], phis[idx])
            w2, l2, _ = f2.world(x[:, 2], x[:, 3], x[:, 4])
            we, le, wo = (w1, l1, w2) if e == 1 else (w2, l2, w1)
            c, cu, cv = _boundary(fe, le, b)
            t = cv[:, None] * we.r_u - cu[:, None] * we.r_v
            return np.concatenate([w1.r - w2.r, c[:, None], np.einsum("ij,ij->i", wo.n, t)[:, None]], -1)

        def fun(x, idx):
            m, k = x.shape[1], len(x)
            E = np.eye(m) * _FD_STEP
            xs = np.concatenate([x] + [x + E[j] for j in range(m)] + [x - E[j] for j in range(m)])
            R = res(xs, np.tile(idx, 2 * m + 1))
            Rp, Rm = R[k:(m + 1) * k].reshape(m, k, -1), R[(m + 1) * k:].reshape(m, k, -1)
            return R[:k], np.moveaxis((Rp - Rm) / (2 * _FD_STEP[:, None, None]), 0, -1)

        r = newton(fun, guess, NewtonOptions(tol=1e-11, maxiter=40, max_backtracks=8), raise_on_failure=False)
        return NewtonResult(r.x, r.residual, r.iterations, r.residual < ACCEPT)

    def solve(self, phis, guess, hint=None):
        """(x, kind, code, residual, ok) at driver angles phis; code = 10 e + b for edges.

        A tangency inside both areas is the contact. Otherwise the longitudinal boundary crossed by
        the tangency point (or `hint` = (e, b)) is tried for edge contact; a tangency point beyond a
        boundary across the profile (tip, fillet) raises GeometryError (not modelled)."""
        n = len(phis)
        x = np.array(guess, float)
        kind = np.zeros(n, int)
        code = np.zeros(n, int)
        res = np.full(n, np.nan)
        r = self.tangency(phis, x)
        conv = r.converged & _in_domain(self.f1, self.f2, r.x)
        con = np.full((n, 2, 5), np.inf)
        if conv.any():
            con[conv] = self.constraints(r.x[conv])
        inside = conv & np.all(con <= self.area_tol, (1, 2))
        x[inside], kind[inside], res[inside] = r.x[inside], SURFACE, r.residual[inside]
        for i in np.flatnonzero(~inside):
            if conv[i]:
                c = con[i].copy()
                prof = np.delete(c, _LONGITUDINAL, axis=1)
                if np.any(prof > self.area_tol):
                    # past a tip or root boundary: edge contact across the profile is not modelled
                    e_, b_ = np.unravel_index(np.argmax(np.where(np.isfinite(prof), prof, -np.inf)), prof.shape)
                    code[i] = -(10 * (e_ + 1) + [0, 1, 4][b_])
                    continue
                lon = c[:, list(_LONGITUDINAL)]
                e_, bi = np.unravel_index(np.argmax(lon), lon.shape)
                cands = [(e_ + 1, _LONGITUDINAL[bi])]
            else:
                cands = []
            if hint is not None and hint not in cands:
                cands.append(hint)
            for e_, b_ in cands:
                g0 = r.x[i] if conv[i] else x[i]
                re = self.edge(phis[i:i + 1], g0[None], e_, b_)
                if not re.converged[0]:
                    continue
                cc = self.constraints(re.x)[0]
                cc[e_ - 1, b_] = 0.0
                if np.all(cc <= self.area_tol):
                    x[i], kind[i], code[i], res[i] = re.x[0], EDGE, 10 * e_ + b_, re.residual[0]
                    break
        return x, kind, code, res, kind > 0


@dataclass(frozen=True, eq=False)
class FaceMeshResult:
    """Reference pair of a sub-drive on a fine grid, transitions, and exact evaluators."""

    mesh: FaceMesh
    phi: np.ndarray  # driver angles of the grid [rad]
    x: np.ndarray  # (n, 5) u1, v1, u2, v2, phi_driven
    kind: np.ndarray  # SURFACE or EDGE
    code: np.ndarray  # 10 e + b of the boundary for edge contact (e: 1 driver, 2 driven; b: 2 outer, 3 inner)
    residual: np.ndarray
    phi_min: float  # driver angle: start of the reference pair's contact (with the forward pair)
    phi_max: float  # driver angle: end (with the backward pair) = phi_min + T
    phi_max_direct: float  # phi_max solved independently (checked equal to phi_min + T)
    driven_min: float  # driven angle at phi_min
    driven_max: float  # driven angle at phi_max
    margins: dict  # smallest distance inside each working-area boundary on [phi_min, phi_max] [mm]
    edge_fraction: float  # part of the contact interval [phi_min, phi_max] in edge contact
    area_tol: float
    elapsed: float
    _spl: dict = field(default_factory=dict, repr=False)

    @property
    def te_ref(self) -> np.ndarray:
        """TE of the reference pair on the grid [rad]."""
        return self.x[:, 4] - self.mesh.ratio * self.phi

    def spline(self) -> CubicSpline:
        """Cubic spline of phi_driven(phi_driver) of the reference pair (dense grid; used for guesses and scans)."""
        if "G" not in self._spl:
            self._spl["G"] = CubicSpline(self.phi, self.x[:, 4])
            self._spl["X"] = CubicSpline(self.phi, self.x, axis=0)
        return self._spl["G"]

    def pair_index(self, phi) -> np.ndarray:
        """Index j of the pair in contact at driver angle phi (0 on [phi_min, phi_max))."""
        T = self.mesh.pitches[0]
        return np.floor((np.asarray(phi, float) - self.phi_min) / T).astype(int)

    def solve(self, phi, j=None):
        """Exact contact of pair j (default: the pair in contact) at driver angles phi: (x (n,5), j, kind).

        x holds the parameters of the reference teeth at the shifted angle and the driven angle of
        pair j itself (x[:, 4])."""
        phi = np.atleast_1d(np.asarray(phi, float))
        j = self.pair_index(phi) if j is None else np.broadcast_to(np.asarray(j, int), phi.shape)
        T, Tn = self.mesh.pitches
        ph = phi - j * T
        self.spline()
        k = np.clip(np.searchsorted(self.phi, ph), 0, len(self.phi) - 1)
        cts = _Contacts(self.mesh, self.area_tol)
        x = np.empty((len(ph), 5))
        kind = np.empty(len(ph), int)
        # points near edge contact on the grid are solved one boundary at a time
        for code in np.unique(self.code[k]):
            sel = np.flatnonzero(self.code[k] == code)
            hint = None if code == 0 else (code // 10, code % 10)
            xs, ks, _, res, ok = cts.solve(ph[sel], self._spl["X"](ph[sel]), hint)
            if not ok.all():
                i = sel[np.flatnonzero(~ok)[0]]
                raise ConvergenceError(f"face-gear TCA ({self.mesh.face.name})", f"phi = {math.degrees(ph[i]):.6f} deg",
                                       float("nan"), 0)
            x[sel], kind[sel] = xs, ks
        x[:, 4] += j * Tn
        return x, j, kind

    def driven(self, phi, j=None) -> np.ndarray:
        """Exact driven angle at driver angles phi [rad]."""
        return self.solve(phi, j)[0][:, 4]

    def driven_fast(self, phi) -> np.ndarray:
        """Driven angle from the spline of the reference pair (pair in contact by the transitions)."""
        phi = np.asarray(phi, float)
        j = self.pair_index(phi)
        T, Tn = self.mesh.pitches
        return self.spline()(phi - j * T) + j * Tn

    def te_cycles(self, cycles: int = 3, steps: int = 60):
        """(phi, te [rad], j, kind) of the sub-drive over `cycles` cycles from phi_min, exact (Fig. 2.3)."""
        T = self.mesh.pitches[0]
        phi = self.phi_min + np.linspace(0.0, cycles * T, cycles * steps + 1)
        x, j, kind = self.solve(phi)
        return phi, x[:, 4] - self.mesh.ratio * phi, j, kind

    def contact_points(self, phi) -> dict:
        """Contact of the pair in contact: point in S_m, on the pinion and on the face gear (their frames),
        the contact ellipse (a, b) [mm] (NaN for edge contact) and the kind."""
        phi = np.atleast_1d(np.asarray(phi, float))
        x, j, kind = self.solve(phi)
        T, Tn = self.mesh.pitches
        f1, f2 = self.mesh.flanks()
        w1, l1, _ = f1.world(x[:, 0], x[:, 1], phi - j * T)
        w2, l2, _ = f2.world(x[:, 2], x[:, 3], x[:, 4] - j * Tn)
        a, b, _, _ = contact_ellipse(w1, w2, 0.0065, np.broadcast_to(f1.mount.axis, w1.r.shape))
        a = np.where(kind == SURFACE, a, np.nan)
        b = np.where(kind == SURFACE, b, np.nan)
        pin, face = (l1.r, l2.r) if self.mesh.driver == "pinion" else (l2.r, l1.r)
        return {"point": w1.r, "pinion": pin, "face": face, "ellipse_a": a, "ellipse_b": b, "kind": kind}


def _prefer(f1: PlacedFlank):
    """Preferred point for (nearly) line contact: the middle of the driver flank's parameter box."""
    su = f1.surface
    uc = 0.5 * (su.u_range[0] + su.u_range[1]) if isinstance(f1.gear, FaceGear) else 0.0
    vc = 0.5 * (su.v_range[0] + su.v_range[1]) if isinstance(f1.gear, FaceGear) else 0.0

    def prefer(x, idx):
        p = x.copy()
        p[:, 0], p[:, 1] = uc, vc
        return p

    return prefer


def _in_domain(f1: PlacedFlank, f2: PlacedFlank, x) -> np.ndarray:
    ok = np.ones(len(x), bool)
    for f, k in ((f1, 0), (f2, 2)):
        s = f.surface
        (u0, u1), (v0, v1) = s.u_range, s.v_range
        ok &= (x[:, k] > u0) & (x[:, k] < u1) & (x[:, k + 1] > v0) & (x[:, k + 1] < v1)
    return ok


ACCEPT = 1e-9  # [mm] residual accepted when Newton (target 1e-11 mm) stalls: conjugate (line) contact of the
# fitted face gear, whose interpolation error (~1e-10 mm) leaves the tangency problem slightly inconsistent


def _newton(f1, f2, phis, guess, strict=False):
    r = newton(tangency_system(f1, f2, phis), guess, NewtonOptions(tol=1e-11, maxiter=40, max_backtracks=8),
               prefer=PreferredPoint(_prefer(f1), PREFER_WEIGHTS), raise_on_failure=False)
    ok = r.residual < ACCEPT
    if strict and not ok.all():
        i = int(np.argmax(np.where(ok, -np.inf, r.residual)))
        raise ConvergenceError("face-gear TCA (tangency)", f"phi = {math.degrees(phis[i]):.6f} deg", float(r.residual[i]),
                               int(r.iterations[i]))
    return NewtonResult(r.x, r.residual, r.iterations, ok)


def _stop_reason(mesh: FaceMesh, code: int) -> str:
    """Words for the code of a failed contact solve."""
    if code >= 0:
        return "no contact found"
    e, b = divmod(-code, 10)
    who = mesh.flanks()[e - 1].gear.name
    return f"past the {['root', 'tip', '', '', 'form circle'][b]} boundary of {who}: edge contact across the profile is not modelled"


def run_face_mesh(mesh: FaceMesh, steps_per_cycle: int = 120, area_tol: float = 1e-7) -> FaceMeshResult:
    """Reference pair over its mesh (block continuation, bounded contact), transitions, working areas."""
    t0 = time.perf_counter()
    if not (isinstance(steps_per_cycle, int) and 8 <= steps_per_cycle <= 5000):
        raise InputError("tca.steps_per_cycle", steps_per_cycle, "an integer in [8, 5000]")
    cts = _Contacts(mesh, area_tol)
    return _finish(cts, trace_reference_pair(mesh, steps_per_cycle, area_tol), t0)


@dataclass(frozen=True, eq=False)
class ReferenceTrace:
    """Contact of the reference pair on a grid of driver angles (:func:`trace_reference_pair`)."""

    phi: np.ndarray  # driver angles [rad]
    x: np.ndarray  # (n, 5) u1, v1, u2, v2, phi_driven
    kind: np.ndarray  # SURFACE or EDGE
    code: np.ndarray  # 10 e + b of the boundary for edge contact
    residual: np.ndarray
    stops: dict  # direction (+1, -1) -> (driver angle [rad], code) where the contact ends


def trace_reference_pair(mesh: FaceMesh, steps_per_cycle: int = 120, area_tol: float = 1e-7,
                         span: float = 1.3) -> ReferenceTrace:
    """Contact of the reference pair on the grid phi_0 + j T/steps, |j| <= span steps, by block continuation
    from the pitch point, and where it ends (`stops`)."""
    cts = _Contacts(mesh, area_tol)
    T = mesh.pitches[0]
    phi0 = mesh.start_angle()
    h = T / steps_per_cycle
    x0, k0, c0, r0, ok0 = cts.solve(np.array([phi0]), np.array([[0.0, 0.0, 0.0, 0.0, mesh.ratio * phi0]]))
    if not (ok0[0] and k0[0] == SURFACE):
        raise ConvergenceError(f"face-gear TCA ({mesh.face.name}, {mesh.pinion.name})",
                               f"the pitch-point position phi = {math.degrees(phi0):.5f} deg", float(r0[0]), 0)
    store = {0: (x0[0], k0[0], c0[0], r0[0])}
    kmax = int(math.ceil(span * steps_per_cycle))
    block = 8
    stops = {}
    for direction in (1, -1):
        last, hint, stop = 0, None, False
        while not stop and abs(last) < kmax:
            ks = [last + direction * (q + 1) for q in range(block)]
            known = [i for i in (last, last - direction, last - 2 * direction) if i in store]
            X = np.array([store[i][0] for i in known])
            deg = min(len(known) - 1, 2)
            if deg == 0:
                guess = np.repeat(X[:1], block, 0)
            else:
                coef = np.polyfit(np.array(known, float), X, deg)
                guess = np.stack([np.polyval(coef[:, m], np.array(ks, float)) for m in range(5)], -1)
            xs, kd, cd, rs, ok = cts.solve(phi0 + h * np.array(ks, float), guess, hint)
            for q, k in enumerate(ks):
                if not ok[q]:
                    # retry alone from the last point (the contact may just have changed kind)
                    xr, kr, cr, rr, okr = cts.solve(np.array([phi0 + h * k]), store[last][0][None], hint)
                    if not okr[0]:
                        stop = True
                        stops[direction] = (phi0 + h * k, int(cr[0]))
                        break
                    xs[q], kd[q], cd[q], rs[q] = xr[0], kr[0], cr[0], rr[0]
                store[k] = (xs[q], kd[q], cd[q], rs[q])
                hint = (cd[q] // 10, cd[q] % 10) if kd[q] == EDGE else None
                last = k
                if not ok[q]:
                    break  # re-predict from the retried point
    ks = np.array(sorted(store))
    phi = phi0 + h * ks
    X = np.array([store[k][0] for k in ks])
    kind = np.array([store[k][1] for k in ks])
    code = np.array([store[k][2] for k in ks])
    res = np.array([store[k][3] for k in ks])
    return ReferenceTrace(phi, X, kind, code, res, stops)


def _finish(cts: _Contacts, trace: ReferenceTrace, t0: float) -> FaceMeshResult:
    """Transitions (Eqs. 2.7-2.8, 2.11-2.12) and working-area margins of a traced reference pair."""
    mesh, area_tol = cts.mesh, cts.area_tol
    phi, X, kind, code, res, stops = trace.phi, trace.x, trace.kind, trace.code, trace.residual, trace.stops
    T, Tn = mesh.pitches
    phi0 = mesh.start_angle()
    h = phi[1] - phi[0]
    G = CubicSpline(phi, X[:, 4])
    Xs = CubicSpline(phi, X, axis=0)

    def exact(p):
        kk = int(np.clip(np.searchsorted(phi, p), 0, len(phi) - 1))
        hint = (code[kk] // 10, code[kk] % 10) if kind[kk] == EDGE else None
        xx, _, _, rr, ok = cts.solve(np.array([p]), Xs(np.array([p])), hint)
        if not ok[0]:
            raise ConvergenceError(f"face-gear TCA ({mesh.face.name})", f"phi = {math.degrees(p):.6f} deg", float(rr[0]), 0)
        return float(xx[0, 4])

    # transitions (Eqs. 2.7-2.8, 2.11-2.12): d(phi) = G(phi) - [G(phi + s T) - s Tn] changes sign
    def transition(s):
        lo_, hi_ = phi[0] - min(0, s) * T, phi[-1] - max(0, s) * T
        if hi_ - lo_ < 2 * h:
            raise GeometryError(mesh.face.name, "contact ratio",
                                f"the reference pair's contact ({math.degrees(phi[-1] - phi[0]):.4f} deg of the driver) "
                                f"does not overlap its neighbour's: contact ratio below 1 within the represented surfaces")
        pp = np.linspace(lo_, hi_, 400)
        dd = G(pp) - (G(pp + s * T) - s * Tn)
        want = 1 if s > 0 else -1  # forward pair hands over (d from - to +); backward takes over (+ to -)
        idx = np.flatnonzero((np.sign(dd[:-1]) != np.sign(dd[1:])) & (np.sign(dd[1:] - dd[:-1]) == want))
        if not len(idx):
            why = "; ".join(f"the contact ends at phi = {math.degrees(p_):.4f} deg ({_stop_reason(mesh, c_)})"
                            for p_, c_ in stops.values())
            raise GeometryError(mesh.face.name, "no transition",
                                f"no simultaneous contact of the reference pair and its {'forward' if s > 0 else 'backward'} "
                                f"pair: the pair leaves its working area before a neighbour takes over ({why})")
        k = idx[np.argmin(np.abs(pp[idx] - phi0))]
        return brentq(lambda p: exact(p) - (exact(p + s * T) - s * Tn), pp[k], pp[k + 1], xtol=1e-13, rtol=1e-15)

    phi_min = transition(+1)
    phi_max = transition(-1)
    if abs(phi_max - phi_min - T) > 1e-8:
        raise ConvergenceError("face-gear TCA transitions", f"phi_max - phi_min = {phi_max - phi_min:.10f} rad vs pitch {T:.10f}",
                               abs(phi_max - phi_min - T), 0)
    # working areas along the reference pair's contact interval
    sel = (phi >= phi_min) & (phi <= phi_min + T)
    xc, kc = X[sel], kind[sel]
    con = cts.constraints(xc)
    margins = {}
    for i, f in enumerate((cts.f1, cts.f2)):
        labels = (["root (pinion tip line)", "tip cone", "outer (L2)", "inner (L1)", "shaper form circle"]
                  if isinstance(f.gear, FaceGear) else ["fillet", "tip", "z_max", "z_min"])
        worst = con[:, i, :len(labels)].max(0)
        margins[f.gear.name] = {lab: float(-w) for lab, w in zip(labels, worst)}
    edge_fraction = float(np.mean(kc == EDGE)) if len(kc) else 0.0
    return FaceMeshResult(mesh, phi, X, kind, code, res, float(phi_min), float(phi_min + T), float(phi_max),
                          exact(phi_min), exact(phi_min + T), margins, edge_fraction, area_tol, time.perf_counter() - t0)
