r"""Planetary train with face gears (Part 2): kinematics, two-stage TCA, installation angle of the planets.

Kinematics (Eqs. 2.1–2.3). Face gears 1 and 4 are coaxial; pinions 2 and 3 are one rigid planet on
carrier c. With the carrier at rest (inverted train) gears 1 and 4 turn the same way:

.. math::
    \frac{\omega_1 - \omega_c}{\omega_4 - \omega_c} = m_{12}^{(c)} m_{34}^{(c)}
    = (-1)\frac{N_2}{N_1}\,(-1)\frac{N_4}{N_3} = i_0 ,

the Willis relation of the train, which gives every use: with gear 4 fixed and the carrier driving,
:math:`m_{c1}^{(4)} = \omega_c/\omega_1 = N_1N_3/(N_1N_3 - N_2N_4)` (Eq. 2.2), :math:`N_1/(N_1 - N_4)` for
:math:`N_2 = N_3` (Eq. 2.3); :math:`N_1N_3 = N_2N_4` makes :math:`i_0 = 1` (no motion: rejected).
Efficiency with a power loss ``loss`` per mesh: the inverted train transmits with
:math:`\eta_0 = (1 - \text{loss})^2`; the torques satisfy :math:`T_1 + T_4 + T_c = 0` and, in the
relative motion, :math:`T_{out}\omega'_{out} = -\eta_0 T_{in}\omega'_{in}` where *in* is the member that
delivers power in the relative motion (found from the sign of its relative power). Example 2.1
(:math:`N_1 = 100`, :math:`N_4 = 88`, 2 % per mesh) gives 8.333 and 77.5 %.

Two-stage TCA (section 2.2). The inverted train (carrier fixed) is two sub-gear drives in series:
reducer — face gear 4 drives pinion 3 (sub-drive 1), pinion 2 drives face gear 1 (sub-drive 2),
TE :math:`\Delta\phi_{14}`; multiplier — face gear 1 drives pinion 2, pinion 3 drives face gear 4,
TE :math:`\Delta\phi_{41}`. Each sub-drive is analysed by :mod:`tca.face.subgear` (its own transition
angles, Eqs. 2.5–2.12). The planet angle :math:`\phi_p` is the angle of pinion 3's reference tooth
in the transverse section through its *apex* (its axis meeting the face-gear axis); pinion 2's
reference tooth is turned by the installation angle :math:`\delta` from pinion 3's in the same
sense (:math:`\phi_2 = \phi_3 = \phi_p`, Fig. 2.2). A pinion's angle in its sub-drive (tooth centre
in the section through its pitch point, at distance :math:`d` from the apex) is
:math:`\phi_{local} = \phi_{apex} + k d`, :math:`k = \sigma\tan\beta/r_p` the screw parameter of the
helicoid — so the two meshes, :math:`d_1 - d_4 = m_t(N_1 - N_4)/(2\sin\gamma)` apart along the
planet axis, are phased by :math:`\delta + k(d_1 - d_4)`.

Steps 1–4 of the report, for each input angle: (1) the input angle is reduced into the interval
:math:`[\phi_{in,min}, \phi_{in,max}]` of the middle pair of the first sub-drive (pair index
:math:`j_A`); (2) its contact gives :math:`\phi_p`; (3) the pair of the second sub-drive is chosen by
:math:`\phi_p` against that sub-drive's transition angles :math:`\phi^*_{p,min}, \phi^*_{p,max}`
(middle pair inside, forward pair before, backward pair after; the *middle* pair of sub-drive 2 is
the one whose contact ends, :math:`\phi^*_{p,max}`, inside the current interval of sub-drive 1), and
its contact gives the output angle; (4) repeat. Integrated TE

.. math:: \Delta\phi_{out} = \phi_{out} - \frac{N_{in}}{N_{pA}}\frac{N_{pB}}{N_{out}}\,\phi_{in}\quad\text{[rad of the output gear]} .

Branches: stretches of constant (pair of sub-drive 1, pair of sub-drive 2); with :math:`N_2 = N_3`
a cycle of the integrated function (one pitch of the input gear) has two parabolic branches, one
when the transitions of the two sub-drives coincide:
:math:`\delta_1 = \delta + \phi_{p,max} - \phi^*_{p,max}` (the report's
:math:`\pi/17 + \phi_{p,max} - \phi^*_{p,max}`). The optimiser minimises the peak-to-peak TE over
one cycle of :math:`\delta` (a scan, then Brent's bounded method), evaluated with spline
interpolants of the exact pair functions and verified with exact solves at the optimum.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from tca.errors import InputError
from tca.face.face_gear import FaceGear
from tca.face.subgear import ARCSEC, SURFACE, FaceMesh, FaceMeshResult, run_face_mesh
from tca.geometry.gear import Gear

__all__ = ["MEMBERS", "basic_ratio", "train_ratio", "train_efficiency", "willis", "FaceTrain", "FaceTrainResult",
           "DeltaScan", "run_face_train", "stage_results", "te_peak_to_peak", "scan_delta", "optimal_delta"]

MEMBERS = ("gear1", "gear4", "carrier")


# ----------------------------------------------------------------------------------------- kinematics
def _check_teeth(n1, n2, n3, n4):
    for name, v in (("N1", n1), ("N2", n2), ("N3", n3), ("N4", n4)):
        if not isinstance(v, (int, np.integer)) or isinstance(v, bool) or v < 3:
            raise InputError(f"teeth.{name}", v, "an integer >= 3")
    if n1 * n3 == n2 * n4:
        raise InputError("teeth", (n1, n2, n3, n4),
                         f"N1 N3 != N2 N4 (here {n1}*{n3} = {n2}*{n4} = {n1 * n3}: the inverted train has ratio 1 and the "
                         f"planetary train cannot move)")


def basic_ratio(n1: int, n2: int, n3: int, n4: int) -> float:
    """i0 = (w1 - wc)/(w4 - wc) = N2 N4 / (N1 N3) (Eq. 2.1)."""
    _check_teeth(n1, n2, n3, n4)
    return n2 * n4 / (n1 * n3)


def willis(n1, n2, n3, n4, **known) -> float:
    """The third angular velocity from two of w1, w4, wc (Willis relation, Eq. 2.1): e.g. willis(..., w4=0, wc=1)."""
    i0 = basic_ratio(n1, n2, n3, n4)
    keys = {"w1", "w4", "wc"}
    if set(known) - keys or len(known) != 2:
        raise InputError("willis", sorted(known), "exactly two of w1, w4, wc")
    if "w1" not in known:
        return known["wc"] + i0 * (known["w4"] - known["wc"])
    if "w4" not in known:
        return known["wc"] + (known["w1"] - known["wc"]) / i0
    return (known["w1"] - i0 * known["w4"]) / (1 - i0)


def _speeds(n, fixed, driver, driven):
    for key, v in (("fixed", fixed), ("input", driver), ("output", driven)):
        if v not in MEMBERS:
            raise InputError(f"train.{key}", v, "one of " + ", ".join(MEMBERS))
    if len({fixed, driver, driven}) != 3:
        raise InputError("train", (fixed, driver, driven), "three different members (fixed, input, output)")
    w = {"gear1": None, "gear4": None, "carrier": None}
    w[fixed] = 0.0
    w[driver] = 1.0
    key = {"gear1": "w1", "gear4": "w4", "carrier": "wc"}
    w[driven] = willis(*n, **{key[m]: w[m] for m in (fixed, driver)})
    return w


def train_ratio(n1: int, n2: int, n3: int, n4: int, fixed: str = "gear4", driver: str = "carrier",
                driven: str = "gear1") -> float:
    """w_input / w_output with member `fixed` at rest (Eq. 2.2; Eq. 2.3 for N2 = N3)."""
    w = _speeds((n1, n2, n3, n4), fixed, driver, driven)
    return w[driver] / w[driven]


def train_efficiency(n1: int, n2: int, n3: int, n4: int, loss_per_mesh: float, fixed: str = "gear4",
                     driver: str = "carrier", driven: str = "gear1") -> float:
    """Efficiency P_out/P_in with a power loss `loss_per_mesh` (fraction) at each of the two meshes."""
    if not (0 <= loss_per_mesh < 0.5):
        raise InputError("train.loss_per_mesh", loss_per_mesh, "a fraction in [0, 0.5)")
    i0 = basic_ratio(n1, n2, n3, n4)
    w = _speeds((n1, n2, n3, n4), fixed, driver, driven)
    eta0 = (1 - loss_per_mesh) ** 2
    wr1, wr4 = w["gear1"] - w["carrier"], w["gear4"] - w["carrier"]  # relative speeds, wr1 = i0 wr4
    # unknown torques T1, T4 (Tc = -T1 - T4); input torque is 1 (with w_in = 1: P_in = 1)
    # relative power: gear 1 delivers if T1 wr1 > 0 -> T4 wr4 = -eta0 T1 wr1, else T1 wr1 = -eta0 T4 wr4
    best = None
    for one_delivers in (True, False):
        if one_delivers:
            # T4 = -eta0 T1 wr1 / wr4 = -eta0 i0 T1
            t1, t4 = 1.0, -eta0 * i0
        else:
            t1, t4 = 1.0, -i0 / eta0  # T1 wr1 = -eta0 T4 wr4 -> T4 = -i0 T1 / eta0
        T = {"gear1": t1, "gear4": t4, "carrier": -t1 - t4}
        s = 1.0 / T[driver]  # scale so that the input torque is 1
        T = {k: v * s for k, v in T.items()}
        p_rel1 = T["gear1"] * wr1
        if (p_rel1 > 0) == one_delivers:
            best = T
    if best is None:  # pragma: no cover - one of the two hypotheses is always consistent
        raise InputError("train", (fixed, driver, driven), "a consistent power flow")
    p_in = best[driver] * w[driver]
    p_out = -best[driven] * w[driven]
    return p_out / p_in


# ----------------------------------------------------------------------------------------- the train
@dataclass(frozen=True)
class FaceTrain:
    """Face gears 1 and 4, planet pinions 2 and 3, installation angle delta [rad], use 'reducer'|'multiplier'."""

    gear1: FaceGear
    gear4: FaceGear
    pinion2: Gear
    pinion3: Gear
    delta: float = math.pi / 17
    use: str = "reducer"
    offset2: float | None = None  # pinion face-width offsets [mm] (default: middle of the face-gear width)
    offset3: float | None = None

    def __post_init__(self):
        if self.use not in ("reducer", "multiplier"):
            raise InputError("train.use", self.use, "'reducer' or 'multiplier'")
        basic_ratio(self.gear1.teeth, self.pinion2.teeth, self.pinion3.teeth, self.gear4.teeth)
        if abs(self.gear1.shaft_angle - self.gear4.shaft_angle) > 1e-12:
            raise InputError(f"{self.gear4.name}.shaft_angle_deg", math.degrees(self.gear4.shaft_angle),
                             f"equal to {self.gear1.name}'s {math.degrees(self.gear1.shaft_angle)} (one planet axis)")
        if not math.isfinite(self.delta):
            raise InputError("train.delta_rad", self.delta, "a finite angle")

    @property
    def teeth(self) -> tuple[int, int, int, int]:
        return self.gear1.teeth, self.pinion2.teeth, self.pinion3.teeth, self.gear4.teeth

    def meshes(self) -> tuple[FaceMesh, FaceMesh]:
        """(stage A, stage B) in the order of the power flow of the inverted train."""
        m2f = FaceMesh(self.gear1, self.pinion2, "pinion", self.offset2)
        m3f = FaceMesh(self.gear4, self.pinion3, "face", self.offset3)
        if self.use == "reducer":
            return m3f, m2f
        return FaceMesh(self.gear1, self.pinion2, "face", self.offset2), FaceMesh(self.gear4, self.pinion3, "pinion",
                                                                                   self.offset3)

    def phase_offsets(self) -> tuple[float, float]:
        """(c_A, c_B): pinion angle in its sub-drive = planet angle phi_p + c (see module docstring)."""
        a, b = self.meshes()
        c3 = self.pinion3.k_screw * (a if self.use == "reducer" else b).apex_distance
        c2 = self.delta + self.pinion2.k_screw * (b if self.use == "reducer" else a).apex_distance
        return (c3, c2) if self.use == "reducer" else (c2, c3)

    @property
    def ratio_inverted(self) -> float:
        """d phi_out / d phi_in of the ideal inverted train."""
        a, b = self.meshes()
        return a.ratio * b.ratio


@dataclass(frozen=True, eq=False)
class FaceTrainResult:
    """Integrated TE of the inverted train over several cycles, with the pairs in contact."""

    train: FaceTrain
    stage_a: FaceMeshResult
    stage_b: FaceMeshResult
    phi_in: np.ndarray  # input face-gear angle [rad]
    phi_p: np.ndarray  # planet angle (apex section of pinion 3) [rad]
    phi_out: np.ndarray  # output face-gear angle [rad]
    te: np.ndarray  # integrated TE [rad of the output gear]
    pair_a: np.ndarray  # pair of sub-drive 1 (0 middle, relative to the first cycle)
    pair_b: np.ndarray  # pair of sub-drive 2 relative to its middle pair of the current cycle (-1, 0, +1)
    edge: np.ndarray  # edge contact in either sub-drive
    transitions: dict  # transition angles (report's names) [rad]
    branch_fractions: np.ndarray  # sizes of the branches of one cycle (fractions of the cycle)
    elapsed: float

    @property
    def te_arcsec(self) -> np.ndarray:
        return self.te / ARCSEC

    @property
    def te_peak_to_peak_arcsec(self) -> float:
        return float(self.te_arcsec.max() - self.te_arcsec.min())

    @property
    def branches_per_cycle(self) -> int:
        return int(np.sum(self.branch_fractions > 1e-6))


def stage_results(train: FaceTrain, steps_per_cycle: int = 120) -> tuple[FaceMeshResult, FaceMeshResult]:
    """TCA of the two sub-drives (reference pairs, transitions) in the order of the power flow."""
    a, b = train.meshes()
    return run_face_mesh(a, steps_per_cycle), run_face_mesh(b, steps_per_cycle)


class _Chain:
    """Kinematic chain of a train at one delta: maps input angles to planet and output angles."""

    def __init__(self, train: FaceTrain, ra: FaceMeshResult, rb: FaceMeshResult, delta: float | None = None):
        self.train, self.ra, self.rb = train, ra, rb
        ca, cb = train.phase_offsets()
        if delta is not None:  # the installation angle enters through pinion 2's offset only
            if train.use == "reducer":
                cb += delta - train.delta
            else:
                ca += delta - train.delta
        self.ca, self.cb = ca, cb
        self.Ta, self.Tpa = ra.mesh.pitches
        self.Tpb, self.Tb = rb.mesh.pitches
        self.ratio = ra.mesh.ratio * rb.mesh.ratio
        # planet-angle transitions
        self.pmin = ra.driven_min - ca  # phi_pmin: sub-drive 1, start of its middle pair
        self.pmax = ra.driven_max - ca
        self.pmin_b = rb.phi_min - cb  # phi*_pmin of the reference pair of sub-drive 2
        self.pmax_b = rb.phi_max - cb

    def b_middle(self, jA):
        """Index of sub-drive 2's middle pair for cycle jA: the one whose end lies in (pmin, pmax] + jA Tpa."""
        lo = self.pmin + jA * self.Tpa
        return (np.floor((lo - self.pmax_b) / self.Tpb) + 1).astype(int)

    def branch_fractions(self) -> np.ndarray:
        """Sizes (fractions of the planet-angle interval of one cycle) of the branches of the first cycle."""
        ends = self.pmax_b + self.b_middle(np.array(0)) * self.Tpb + np.arange(0, 8) * self.Tpb
        cuts = ends[(ends > self.pmin + 1e-15) & (ends < self.pmax - 1e-15)]
        pts = np.concatenate([[self.pmin], cuts, [self.pmax]])
        return np.diff(pts) / (self.pmax - self.pmin)

    def evaluate(self, phi_in, exact: bool = True):
        """(phi_p, phi_out, te, pair_a, pair_b relative to the middle pair of sub-drive 2, edge contact)."""
        phi_in = np.asarray(phi_in, float)
        jA = self.ra.pair_index(phi_in)
        edge = np.zeros(phi_in.shape, bool)
        if exact:
            xa, _, ka = self.ra.solve(phi_in, jA)
            phi_a, edge = xa[:, 4], ka != SURFACE
        else:
            phi_a = self.ra.driven_fast(phi_in)
        phi_p = phi_a - self.ca
        phi_b = phi_p + self.cb
        jB = self.rb.pair_index(phi_b)
        if exact:
            xb, _, kb = self.rb.solve(phi_b, jB)
            phi_out, edge = xb[:, 4], edge | (kb != SURFACE)
        else:
            phi_out = self.rb.driven_fast(phi_b)
        te = phi_out - self.ratio * phi_in
        return phi_p, phi_out, te, jA, jB - self.b_middle(jA), edge


def te_peak_to_peak(train: FaceTrain, ra: FaceMeshResult, rb: FaceMeshResult, delta: float, samples: int = 400,
                    exact: bool = False) -> float:
    """Peak-to-peak integrated TE over one cycle of the input [rad], cusps included exactly (via splines)."""
    ch = _Chain(train, ra, rb, delta)
    phi = ra.phi_min + np.linspace(0.0, ch.Ta, samples + 1)[:-1]
    # the cusp: input angle where sub-drive 2 changes pair inside the cycle
    extra = []
    ends = ch.pmax_b + ch.b_middle(np.array(0)) * ch.Tpb + np.arange(0, 4) * ch.Tpb
    G = ra.spline()
    for e in ends[(ends > ch.pmin) & (ends < ch.pmax)]:
        target = e + ch.ca
        extra.append(brentq(lambda x: float(G(x)) - target, ra.phi_min, ra.phi_max, xtol=1e-14))
        extra.append(extra[-1] - 1e-9)
    phi = np.concatenate([phi, extra])
    te = ch.evaluate(phi, exact=exact)[2]
    return float(te.max() - te.min())


@dataclass(frozen=True, eq=False)
class DeltaScan:
    """Integrated peak-to-peak TE over one cycle of delta, single-branch and optimal delta."""

    delta: np.ndarray  # [rad]
    te_pp: np.ndarray  # [rad]
    delta_single: float  # transitions of the two sub-drives coincide [rad]
    te_single: float
    delta_equal: float  # two branches of equal size [rad]
    te_equal: float
    delta_opt: float
    te_opt: float
    te_opt_exact: float  # verified with exact solves


def _wrap(x, lo, period):
    return lo + (x - lo) % period


def scan_delta(train: FaceTrain, ra: FaceMeshResult, rb: FaceMeshResult, samples: int = 73,
               around: float | None = None) -> DeltaScan:
    """TE(delta) over one cycle of delta, the optimiser (minimum peak-to-peak), single/equal-branch deltas."""
    ch = _Chain(train, ra, rb)
    period = train.pinion2.pitch_angle  # nothing changes when pinion 2 is turned by one pitch
    lo = (train.delta if around is None else around) - 0.5 * period
    ds = lo + np.linspace(0.0, period, samples + 1)[:-1]
    f = np.array([te_peak_to_peak(train, ra, rb, d) for d in ds])
    # single branch: phi*_pmax(delta) = phi_pmax, phi* moves by -(delta - delta0) (reducer) / ... (multiplier)
    sgn = _delta_sign(train)
    d_single = _wrap(train.delta + sgn * (ch.pmax_b - ch.pmax), lo, period)
    d_equal = _wrap(d_single + 0.5 * period, lo, period)
    k = int(np.argmin(f))
    a, b = ds[k] - period / samples, ds[k] + period / samples
    res = minimize_scalar(lambda d: te_peak_to_peak(train, ra, rb, d), bounds=(a, b), method="bounded",
                          options={"xatol": 1e-7})
    d_opt, te_opt = float(res.x), float(res.fun)
    if f[k] < te_opt:
        d_opt, te_opt = float(ds[k]), float(f[k])
    te_opt_exact = te_peak_to_peak(train, ra, rb, d_opt, samples=240, exact=True)
    return DeltaScan(ds, f, float(d_single), te_peak_to_peak(train, ra, rb, d_single), float(d_equal),
                     te_peak_to_peak(train, ra, rb, d_equal), d_opt, te_opt, te_opt_exact)


def _delta_sign(train: FaceTrain) -> float:
    """d(phi*_pmax)/d(delta) * -1: +1 when delta shifts sub-drive 2 (reducer), -1 when it shifts sub-drive 1."""
    return 1.0 if train.use == "reducer" else -1.0


def optimal_delta(train: FaceTrain, steps_per_cycle: int = 120) -> tuple[float, float]:
    """(delta, peak-to-peak TE [rad]) minimising the integrated TE over one cycle of delta."""
    ra, rb = stage_results(train, steps_per_cycle)
    s = scan_delta(train, ra, rb)
    return s.delta_opt, s.te_opt_exact


def run_face_train(train: FaceTrain, cycles: int = 3, steps_per_cycle: int = 60, mesh_steps: int = 120,
                   stages=None) -> FaceTrainResult:
    """Integrated TE of the inverted train over `cycles` cycles of the input gear (Steps 1-4, exact solves)."""
    t0 = time.perf_counter()
    if not (isinstance(cycles, int) and 1 <= cycles <= 50):
        raise InputError("tca.cycles", cycles, "an integer in [1, 50]")
    if not (isinstance(steps_per_cycle, int) and 4 <= steps_per_cycle <= 2000):
        raise InputError("tca.steps_per_cycle", steps_per_cycle, "an integer in [4, 2000]")
    ra, rb = stages if stages is not None else stage_results(train, mesh_steps)
    ch = _Chain(train, ra, rb)
    phi_in = ra.phi_min + np.linspace(0.0, cycles * ch.Ta, cycles * steps_per_cycle + 1)
    # add the cusps (changes of pair of sub-drive 2) so that the branches end exactly
    G = ra.spline()
    cusps = []
    for jA in range(cycles):
        ends = ch.pmax_b + ch.b_middle(np.array(jA)) * ch.Tpb + np.arange(0, 4) * ch.Tpb
        lo, hi = ch.pmin + jA * ch.Tpa, ch.pmax + jA * ch.Tpa
        for e in ends[(ends > lo + 1e-12) & (ends < hi - 1e-12)]:
            target = e + ch.ca - jA * ch.Tpa
            x = brentq(lambda x: float(G(x)) - target, ra.phi_min, ra.phi_max, xtol=1e-14) + jA * ch.Ta
            cusps += [x - 1e-10, x]
    # the ends of the cycles of sub-drive 1 (its transitions), reached from the previous pair as well
    ends = ra.phi_min + ch.Ta * np.arange(1, cycles + 1) - 1e-10
    phi_in = np.sort(np.concatenate([phi_in, cusps, ends]))
    phi_p, phi_out, te, ja, jb, edge = ch.evaluate(phi_in, exact=True)
    trans = {
        "phi_in_min": ra.phi_min, "phi_in_max": ra.phi_max,
        "phi_p_min": ch.pmin, "phi_p_max": ch.pmax,
        "phi_p_min_star": ch.pmin_b + ch.b_middle(np.array(0)) * ch.Tpb,
        "phi_p_max_star": ch.pmax_b + ch.b_middle(np.array(0)) * ch.Tpb,
    }
    return FaceTrainResult(train, ra, rb, phi_in, phi_p, phi_out, te, ja, jb, edge, trans, ch.branch_fractions(),
                           time.perf_counter() - t0)
