r"""TCA of single subgear drives of the planetary train with the carrier at rest (section 1.4).

A single subgear drive is sun member :math:`1_k`, planet :math:`2_k^{(i)}` and ring :math:`3_k`.
Its ten tangency equations (Eq. 1.9 for 1–2 and for 2–3) are solved as two five-equation
subsystems: sun → planet gives :math:`\phi_2(\phi_1)`, which is the input of planet → ring,
giving :math:`\phi_3(\phi_2)`. Each subsystem is a pair TCA (:func:`tca.pair.analysis.run_pair_tca`, the
"largest Δφ" rule for neighbouring tooth pairs) in its own pair frame with explicit mounts.

Frames. :math:`S_f`: sun axis :math:`z_f`, the sun turns positively. Shaft *i* sits at
:math:`\theta_i = 2\pi(i-1)/n` on the carrier, centre :math:`E e_r(\theta_i)`, :math:`E = r_1 + r_2`;
members at :math:`z_f = \pm z_m`. With the carrier at rest the planets and the ring turn negatively
in :math:`S_f`, so their frames have :math:`z = -z_f` (each gear turns positively in its own frame).
The sun's driving flank (+1) pushes the planet's trailing flank (−1, coast profile :math:`a_{cc}`);
the planet's leading flank (+1, driving profile :math:`a_{cd}`) pushes the ring's trailing flank
(−1). Pair frame 1 is :math:`S_f` turned by :math:`\theta_i` about :math:`z_f` (origin at the member
plane); pair frame 2 has its origin at the planet's nominal centre, :math:`x = e_r`, :math:`z=-z_f`.
Planet angles: :math:`\phi_2' = \phi_2 + \pi + \pi/N_2` (pair 2 vs pair 1); ring angle in
:math:`S_f` (about :math:`-z_f`): :math:`\phi_3 = \phi_3' - \theta_i + \pi/N_3`.

Transmission errors of the ring, absolute (Eq. 1.13 through the planet):

.. math::
    \Delta\phi_3^{(i)}(\phi_1) = \phi_3 - \frac{N_1}{N_3}\phi_1 - \frac{\pi (N_2 + 2)}{N_3}
    \pmod{2\pi/N_3} = \frac{N_2}{N_3}\,\Delta\phi_2^{(12)}(\phi_1 - \theta_i)
    + \Delta\phi_3^{(23)}(\phi_2'),

zero for ideal involute gears at every planet: the remainder
:math:`-\theta_i(N_1+N_3)/N_3 = -2\pi(i-1)a/N_3` is a whole number of ring pitches by Eq. (1.3).
So :math:`\Delta\phi_3^{(i)}` compares all planets directly: the planet with the largest value is
in mesh, the others have the backlash :math:`|M_jM_i|` (Fig. 1.4).

Each mesh is solved over one cycle and used periodically (:class:`tca.pair.te.MeshTE`): the TE is the largest
of the reference pair's branch shifted by whole pitches. The sun mesh is read on its own grid
(``steps_per_cycle`` a multiple of n puts :math:`\phi_1 - \theta_i` on it for every planet); the ring
mesh is needed at :math:`\phi_2'`, between grid points, where each branch is interpolated linearly
(error :math:`\le h^2\max|f''|/8`, ~0.05 arcsec at 20 steps) and the kinks between pairs stay exact.

Axial regulation moves a member along its axis; the turn of the screw motion (section 1.3) is
absorbed by the planet angle, which the sun mesh fixes, so only the axial position matters here.
Both pair frames turn with the shaft, so the two pair TCAs of a member depend on its errors and
axial position only, not on the shaft's place on the carrier (:func:`subgear_meshes`); the shaft
angle enters through the composition above (:func:`compose_te`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from tca.errors import GeometryError, InputError
from tca.pair.gear_pair import GearPair
from tca.pair.analysis import ARCSEC, TCAOptions, run_pair_tca
from tca.pair.te import MeshTE  # the one home of a pair's periodic TE; kept importable from here
from tca.planetary.train import DoubleHelicalTrain, ShaftErrors
from tca.numerics.transforms import Mount, rot_x, rot_y, rot_z

__all__ = ["MeshTE", "SubgearTE", "member_pose", "subgear_pairs", "phi1_grid", "subgear_meshes", "run_subgear_tca",
           "compose_te", "periodic_peak"]


def member_pose(train: DoubleHelicalTrain, i: int, member: str, errors: ShaftErrors = ShaftErrors(),
                dz: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Origin [mm] and R0 of planet member (shaft i 0-based, 'a'/'b') in S_f, phase pi/N2 convention."""
    th = train.carrier_angle(i)
    er = np.array([math.cos(th), math.sin(th), 0.0])
    et = np.array([-math.sin(th), math.cos(th), 0.0])
    R_err = rot_z(th) @ rot_x(errors.d_gamma) @ rot_z(-th)  # shaft turned about e_r through its centre
    centre = train.center_distance * er - errors.d_ex * et
    ez = np.array([0.0, 0.0, 1.0])
    axis = R_err @ ez
    origin = centre + train.member_sign(member) * train.member_offset * axis + dz * train.dz_direction(member) * axis
    R0 = R_err @ rot_z(th) @ rot_y(math.pi)
    return origin, R0


def subgear_pairs(train: DoubleHelicalTrain, i: int, member: str, errors: ShaftErrors = ShaftErrors(),
                  dz: float = 0.0) -> tuple[GearPair, GearPair]:
    """(sun -> planet, planet -> ring) pairs of a single subgear drive, in their pair frames."""
    sun, planet, ring = train.gears(member)
    th = train.carrier_angle(i)
    zk = train.member_sign(member) * train.member_offset
    E = train.center_distance
    o, R0 = member_pose(train, i, member, errors, dz)
    A1 = rot_z(-th)
    p1 = GearPair(sun, planet, mount1=Mount(np.zeros(3), np.eye(3), 0.0),
                  mount2=Mount(A1 @ o - np.array([0.0, 0.0, zk]), A1 @ R0, math.pi / planet.teeth))
    A2 = rot_x(math.pi) @ rot_z(-th)
    c_nom = np.array([E * math.cos(th), E * math.sin(th), zk])
    Q2 = A2 @ R0 @ rot_z(-math.pi)
    p2 = GearPair(planet, ring, mount1=Mount(A2 @ (o - c_nom), Q2, 0.0),
                  mount2=Mount(np.array([-E, 0.0, 0.0]), np.eye(3), math.pi / ring.teeth))
    return p1, p2


def phi1_grid(train: DoubleHelicalTrain, opts: TCAOptions) -> np.ndarray:
    """Global sun angles φ1 [rad] over opts.cycles sun pitches, on the grid of every planet's sun mesh."""
    s = opts.steps_per_cycle
    if s % train.planets:
        raise InputError("tca.steps_per_cycle", s, f"a multiple of the number of planets n = {train.planets} (the sun "
                         "meshes of all planets are then sampled on one grid)")
    sun = train.sun
    p = sun.surface(1).evaluate(0.0, 0.0).r  # pitch point of the driving flank
    phi0 = -math.atan2(p[1], p[0])
    h = 2 * math.pi / sun.teeth / s
    return phi0 + h * np.arange(opts.cycles * s + 1)


@dataclass(frozen=True, eq=False)
class SubgearTE:
    """Single subgear drive (shaft i, member k): Δφ3(φ1) and its two meshes."""

    shaft: int  # 0-based
    member: str
    errors: ShaftErrors
    dz: float  # axial regulation [mm]
    phi1: np.ndarray  # global sun angles [rad]
    te3: np.ndarray  # Δφ3 [rad]
    te12: np.ndarray  # Δφ2 of the sun mesh at φ1 - θ_i [rad]
    te23: np.ndarray  # Δφ3' of the ring mesh at φ2' [rad]
    mesh12: MeshTE
    mesh23: MeshTE

    @property
    def te3_arcsec(self) -> np.ndarray:
        return self.te3 / ARCSEC

    def peak(self) -> float:
        """Largest Δφ3 over the (whole-cycle) grid, refined by a parabola through three samples [rad]."""
        return periodic_peak(self.te3)

    @property
    def edge_contact(self) -> bool:
        return self.mesh12.result.edge_contact or self.mesh23.result.edge_contact


def periodic_peak(y: np.ndarray) -> float:
    """Maximum of a periodic sampled function (y[-1] repeats y[0]), refined by a parabola through 3 points."""
    v = np.asarray(y, float)[:-1]
    j = int(np.argmax(v))
    a, b, c = v[j - 1], v[j], v[(j + 1) % len(v)]
    den = a - 2 * b + c
    if den < 0:
        t = 0.5 * (a - c) / den
        if abs(t) <= 1:
            return float(b - 0.25 * (a - c) * t)
    return float(b)


def compose_te(train: DoubleHelicalTrain, i: int, member: str, mesh12: MeshTE, mesh23: MeshTE,
               phi1: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Δφ3, Δφ2 (sun mesh) and Δφ3' (ring mesh) [rad] at the global sun angles phi1 (module docstring)."""
    _, planet, ring = train.gears(member)
    N1, N2, N3 = train.sun.teeth, planet.teeth, ring.teeth
    th = train.carrier_angle(i)
    ph1 = np.asarray(phi1, float) - th
    te12 = mesh12(ph1)
    ph2p = (N1 / N2) * ph1 + te12 + math.pi + math.pi / N2
    te23 = mesh23(ph2p)
    ph3 = (N2 / N3) * ph2p + te23 - th + math.pi / N3
    d = ph3 - (N1 / N3) * np.asarray(phi1, float) - math.pi * (N2 + 2) / N3
    p3 = 2 * math.pi / N3
    te3 = d + i * train.a * p3  # the remainder -theta_i (N1 + N3) / N3 is -i a ring pitches (Eq. 1.3)
    if np.abs(te3).max() > p3 / 4:
        raise GeometryError("train", "phasing", f"shaft {i + 1}: ring TE of {np.abs(te3).max() / ARCSEC:.1f} arcsec "
                            "exceeds a quarter of the ring pitch; the subgear meshes are not in their mesh cycle")
    return te3, te12, te23


def subgear_meshes(train: DoubleHelicalTrain, member: str, errors: ShaftErrors = ShaftErrors(), dz: float = 0.0,
                   opts: TCAOptions = TCAOptions(), cache: dict | None = None) -> tuple[MeshTE, MeshTE]:
    """Sun and ring meshes (one cycle each) of a member with these errors and axial position, any shaft."""
    key = (member, errors.d_ex, errors.d_gamma, float(dz), opts.steps_per_cycle)
    if cache is not None and key in cache:
        return cache[key]
    p1, p2 = subgear_pairs(train, 0, member, errors, dz)
    one = replace(opts, cycles=1)  # the meshes are periodic: one cycle each
    out = MeshTE.from_result(run_pair_tca(p1, one)), MeshTE.from_result(run_pair_tca(p2, one))
    if cache is not None:
        cache[key] = out
    return out


def run_subgear_tca(train: DoubleHelicalTrain, i: int, member: str, errors: ShaftErrors = ShaftErrors(),
                    dz: float = 0.0, opts: TCAOptions = TCAOptions(), phi1: np.ndarray | None = None,
                    cache: dict | None = None) -> SubgearTE:
    """TCA of the single subgear drive of shaft i (0-based), member 'a'/'b': two pair TCAs, composed."""
    if not 0 <= i < train.planets:
        raise InputError("shaft", i + 1, f"in [1, {train.planets}]")
    if phi1 is None:
        phi1 = phi1_grid(train, opts)
    m12, m23 = subgear_meshes(train, member, errors, dz, opts, cache)
    te3, te12, te23 = compose_te(train, i, member, m12, m23, phi1)
    return SubgearTE(i, member, errors, dz, np.asarray(phi1, float), te3, te12, te23, m12, m23)
