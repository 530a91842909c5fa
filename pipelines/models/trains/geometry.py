r"""The meshes of a planetary train in the carrier frame: where each mesh's pair frame sits, which bodies it joins.

Frame. :math:`S_f` is the carrier frame of Part 1 (:mod:`tca.planetary.subgear`): sun axis :math:`z_f`, the
sun turns positively, planet i at :math:`\theta_i = 2\pi i/n` (0-based) on the x axis turned by
:math:`\theta_i`. With the carrier as the frame, the ring turns (backwards) and the sun turns relative
to the carrier by :math:`\psi_1 = \phi_1 - \phi_c`; with the ring held and the carrier the output
(the conventions of the train LTCA), :math:`\phi_c = m_{c1}\phi_1`, :math:`m_{c1} = N_1/(N_1 + N_3)`, so
:math:`\psi_1 = (1 - m_{c1})\phi_1` and one carrier revolution is :math:`N_3` mesh cycles (one sun pitch of
:math:`\psi_1` each).

Meshes. Planet i, member k (a, b of a twin; one member '' otherwise) meshes with the sun (the sun drives
the planet's −1 flank with its +1 flank) and with the ring (the planet's +1 flank drives the ring's −1
flank). Each mesh is a :class:`tca.pair.gear_pair.GearPair` in its own pair frame, exactly as the Part 1
train TCA builds it (:func:`tca.planetary.subgear.subgear_pairs`), mapped to :math:`S_f` by

.. math::
    \text{sun mesh: } x_f = A_1^T(x + z_k e_z),\qquad \text{ring mesh: } x_f = A_2^T x + (E\cos\theta_i, E\sin\theta_i, z_k),

:math:`A_1 = R_z(-\theta_i)`, :math:`A_2 = R_x(\pi)R_z(-\theta_i)`, :math:`z_k` the member's plane (0 for a
single member). The pair frames turn with the planet, so a pair depends on its member's errors only and
one pair TCA serves every planet with the same errors (:attr:`MeshSite.key`). The driver angles at
:math:`\psi_1` with every body at its nominal place (the reference configuration q = 0 of the solve):

.. math::
    \text{sun mesh: } \phi = \psi_1 - \theta_i,\qquad
    \text{ring mesh: } \phi' = \frac{N_1}{N_2}(\psi_1 - \theta_i) + \pi + \frac{\pi}{N_2}

(the planet's angle in pair frame 2, :func:`tca.planetary.subgear.compose_te`); the driven bodies' nominal
angles are :math:`(N_1/N_2)\phi` and :math:`(N_2/N_3)\phi'`, the same ring for every planet by Eq. (1.3).

Twin members that are mirror images (no shaft-angle error, equal axial regulation: member b repeats member a
in the Part 1 TCA) share member a's pair: member b's slices are member a's reflected in its pair frame's plane
z = 0 (:attr:`MeshSite.mirror`).

Errors that are small rigid offsets of a body (the pin errors, a fixed member's centre error, run-outs) are
prescribed translations :math:`\mathbf e_X(\psi_1)` of the bodies' teeth in :math:`S_f` (:func:`offsets`), first
order in the error as :mod:`tca.isostatic.linear`: with :math:`R(\cdot)` the plane rotation and
:math:`D = \mathrm{diag}(-1, 1)`,

* planet i: :math:`R(\theta_i)(\Delta r_c, \Delta E_t) + R(\theta_i)\,D\,R(a_i)\,\boldsymbol\varepsilon_i`,
  :math:`a_i = (N_1/N_2)(\psi_1-\theta_i) + \pi/N_2`, plus :math:`R(-\phi_c)\Delta\mathbf E_c` (carrier centre);
* sun: :math:`R(-\phi_c)\Delta\mathbf E_1 + R(\psi_1)\boldsymbol\varepsilon_1`;
* ring: :math:`R(-\phi_c)(\Delta\mathbf E_3 + D\,R(\rho_0)\boldsymbol\varepsilon_3)`, :math:`\rho_0 = -\pi + \pi(N_2+2)/N_3`,

:math:`\Delta E_t` along the carrier's rotation (Part 3, Eq. 3.12; Part 1's :math:`\Delta E_x = -\Delta E_t`),
the centre errors in the fixed frame. The errors of Part 1 (:math:`\Delta E_x`, :math:`\Delta\gamma`, the
regulation :math:`\Delta Z`) are built into the pairs exactly, as by its train TCA.

Regulation and the twin. A twin planet is one rigid body. Without regulation its members sit on the shaft as
made (at the nominal angle). Part 1's regulation moves each member along its axis while the sun mesh turns it
(the screw motion "absorbed by the planet angle, which the sun mesh fixes", :mod:`tca.planetary.subgear`): a
regulated member is mounted at its own sun-contact angle, turned on the shaft by
:math:`\delta_k = \overline{\Delta\phi_2^{(k)}}` (the mean TE of its sun mesh, with its errors and ΔZ), which is
the member independence the train TCA and its regulation assume. (``regulated``; the model computes δ_k.)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from mesher.placement import Pose
from tca.errors import InputError
from tca.geometry.gear import Gear
from tca.pair.gear_pair import GearPair
from tca.planetary.subgear import member_pose, subgear_pairs
from tca.planetary.train import DoubleHelicalTrain
from tca.numerics.transforms import rot_x, rot_y, rot_z

__all__ = ["MeshSite", "TrainLayout", "TrainErrors", "double_helical_layout", "single_layout", "offsets", "rot2",
           "REFLECT"]

REFLECT = np.array([[-1.0, 0.0], [0.0, 1.0]])  # D: x -> -x in the plane


def rot2(a) -> np.ndarray:
    """Plane rotations R(a), shape (..., 2, 2)."""
    a = np.asarray(a, float)
    c, s = np.cos(a), np.sin(a)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


@dataclass(frozen=True, eq=False)
class MeshSite:
    """One mesh of the train: planet ``planet`` (0-based), member ``member``, with the sun or the ring."""

    planet: int
    member: str  # 'a', 'b' or '' (a single member)
    kind: str  # 'sun' or 'ring'
    key: tuple  # the pair (and its TCA) this mesh uses: (member geometry key, kind)
    mirror: bool  # slices of ``key``'s pair reflected z -> -z in the pair frame (member b of a mirrored twin)
    frame: Pose  # pair frame -> S_f

    @property
    def name(self) -> str:
        return f"{self.kind}.p{self.planet + 1}{self.member}"


@dataclass(frozen=True, eq=False)
class TrainLayout:
    """The meshes of a train (module docstring), its bodies' axes in S_f and the distinct pairs."""

    sun: Gear
    planet: Gear
    ring: Gear
    planets: int
    members: tuple  # ('a', 'b') for a twin, ('',) otherwise
    sites: tuple  # MeshSite
    pairs: dict  # key -> GearPair (pair frame)
    planet_origin: np.ndarray  # (n, 3) a point of each planet's axis [mm]
    planet_axis: np.ndarray  # (n, 3) the planet's own z axis (it turns positively about it)
    center_distance: float  # E [mm]
    twin: object = None  # the DoubleHelicalTrain of Part 1 (None for a single train)
    labels: dict = field(default_factory=dict)  # key -> readable name of the pair
    regulated: bool = False  # Part 1: members mounted at their own sun-contact angle (module docstring)

    @property
    def teeth(self) -> tuple[int, int, int]:
        return self.sun.teeth, self.planet.teeth, self.ring.teeth

    @property
    def carrier_ratio(self) -> float:
        """m_c1 = N1 / (N1 + N3): carrier over sun with the ring held."""
        N1, _, N3 = self.teeth
        return N1 / (N1 + N3)

    @property
    def theta(self) -> np.ndarray:
        return 2 * math.pi * np.arange(self.planets) / self.planets

    def driver_angle(self, site: MeshSite, psi1: float) -> float:
        """The driver's angle [rad] in the site's pair frame with the train at ψ1 (nominal bodies, module docstring)."""
        N1, N2, _ = self.teeth
        ph1 = psi1 - self.theta[site.planet]
        if site.kind == "sun":
            return ph1
        return (N1 / N2) * ph1 + math.pi + math.pi / N2


def _frames(theta: float, zk: float, E: float) -> tuple[Pose, Pose]:
    A1 = rot_z(-theta)
    A2 = rot_x(math.pi) @ rot_z(-theta)
    return (Pose(A1.T, A1.T @ np.array([0.0, 0.0, zk])),
            Pose(A2.T, np.array([E * math.cos(theta), E * math.sin(theta), zk])))


def double_helical_layout(train: DoubleHelicalTrain, errors, dz, regulated: bool = False) -> TrainLayout:
    """Part 1's train: every shaft i with its errors ``errors[i]`` (:class:`ShaftErrors`) and axial regulation
    ``dz[i] = (ΔZ_a, ΔZ_b)`` [mm], both members; the pairs of :func:`tca.planetary.subgear.subgear_pairs`.
    ``regulated``: the members are mounted at their own sun-contact angles (module docstring)."""
    n = train.planets
    errors, dz = tuple(errors), tuple(tuple(float(v) for v in d) for d in dz)
    if len(errors) != n or len(dz) != n:
        raise InputError("installment", len(errors), f"errors and regulation for each of the {n} planet shafts")
    sites, pairs, labels = [], {}, {}
    origins, axes = [], []
    E = train.center_distance
    for i, (e, (dza, dzb)) in enumerate(zip(errors, dz)):
        o, R0 = member_pose(train, i, "a", e, 0.0)
        origins.append(o)
        axes.append(R0[:, 2])
        mirrored = e.d_gamma == 0.0 and dza == dzb
        for k, d in (("a", dza), ("b", dzb)):
            gk = ("a" if mirrored else k, e.d_ex, e.d_gamma, d)
            if gk not in pairs:
                p12, p23 = subgear_pairs(train, 0, gk[0], e, d)
                for kind, p in (("sun", p12), ("ring", p23)):
                    pairs[(gk, kind)] = p
                    labels[(gk, kind)] = (f"{kind} mesh, member {gk[0]}, dEx {e.d_ex * 1e3:g} um, "
                                          f"dgamma {math.degrees(e.d_gamma) * 60:g}', dZ {d:g} mm")
            zk = train.member_sign(k) * train.member_offset
            f1, f2 = _frames(train.carrier_angle(i), zk, E)
            for kind, fr in (("sun", f1), ("ring", f2)):
                sites.append(MeshSite(i, k, kind, (gk, kind), mirrored and k == "b", fr))
    return TrainLayout(train.sun, train.planet, train.ring, n, ("a", "b"), tuple(sites), pairs, np.array(origins),
                       np.array(axes), E, train, labels, bool(regulated))


def single_layout(sun: Gear, planet: Gear, ring: Gear, planets: int) -> TrainLayout:
    """A train of one member: sun, ``planets`` equal planets, ring, standard centre distances; every planet's
    meshes are the same two pairs (their errors are offsets, :func:`offsets`)."""
    bare = [g if g.runout == 0 else _no_runout(g) for g in (sun, planet, ring)]
    sun, planet, ring = bare
    E = sun.r_p + planet.r_p
    p12 = GearPair(sun, planet)
    p23 = GearPair(planet, ring)
    pairs = {(("", 0.0, 0.0, 0.0), "sun"): p12, (("", 0.0, 0.0, 0.0), "ring"): p23}
    labels = {k: f"{k[1]} mesh" for k in pairs}
    sites, origins, axes = [], [], []
    for i in range(planets):
        th = 2 * math.pi * i / planets
        f1, f2 = _frames(th, 0.0, E)
        for kind, fr in (("sun", f1), ("ring", f2)):
            sites.append(MeshSite(i, "", kind, (("", 0.0, 0.0, 0.0), kind), False, fr))
        origins.append([E * math.cos(th), E * math.sin(th), 0.0])
        axes.append((rot_z(th) @ rot_y(math.pi))[:, 2])
    return TrainLayout(sun, planet, ring, planets, ("",), tuple(sites), pairs, np.array(origins), np.array(axes), E,
                       None, labels)


def _no_runout(g: Gear) -> Gear:
    from dataclasses import replace

    return replace(g, runout=0.0, runout_phase=0.0)


@dataclass(frozen=True)
class TrainErrors:
    """Small rigid errors entered as prescribed translations (module docstring) [mm]: per planet the pin error
    (radial, tangential) and run-out vector (gear frame), the sun's and ring's run-out vectors (gear frames), the
    centre errors of the sun, carrier and ring (fixed frame, of members whose axes are held)."""

    pins: tuple = ()  # ((Δr_c, ΔE_t), ...) per planet
    planet_runout: tuple = ()  # ((x, y), ...) per planet
    sun_runout: tuple = (0.0, 0.0)
    ring_runout: tuple = (0.0, 0.0)
    sun_center: tuple = (0.0, 0.0)
    carrier_center: tuple = (0.0, 0.0)
    ring_center: tuple = (0.0, 0.0)

    def stationary(self) -> bool:
        """True when nothing varies with the carrier angle (only pin errors): the loads repeat every mesh cycle."""
        z = (0.0, 0.0)
        return (all(tuple(r) == z for r in self.planet_runout) and tuple(self.sun_runout) == z
                and tuple(self.ring_runout) == z and tuple(self.sun_center) == z and tuple(self.carrier_center) == z
                and tuple(self.ring_center) == z)


def offsets(layout: TrainLayout, errors: TrainErrors, psi1: float) -> dict:
    """Prescribed translations (2,) [mm] in S_f of the sun's, ring's and each planet's teeth at ψ1 (module docstring):
    {'sun': e, 'ring': e, 'planets': (n, 2)}."""
    N1, N2, N3 = layout.teeth
    mc = layout.carrier_ratio
    phic = mc * psi1 / (1.0 - mc)
    back = rot2(-phic)
    n = layout.planets
    th = layout.theta
    pl = np.zeros((n, 2))
    if errors.pins:
        pl += np.einsum("nij,nj->ni", rot2(th), np.asarray(errors.pins, float))
    if errors.planet_runout:
        a = (N1 / N2) * (psi1 - th) + math.pi / N2
        eps = np.asarray(errors.planet_runout, float)
        pl += np.einsum("nij,nj->ni", rot2(th) @ REFLECT @ rot2(a), eps)
    pl += back @ np.asarray(errors.carrier_center, float)
    sun = back @ np.asarray(errors.sun_center, float) + rot2(psi1) @ np.asarray(errors.sun_runout, float)
    rho0 = -math.pi + math.pi * (N2 + 2) / N3
    ring = back @ (np.asarray(errors.ring_center, float) + REFLECT @ rot2(rho0) @ np.asarray(errors.ring_runout, float))
    return {"sun": sun, "ring": ring, "planets": pl}
