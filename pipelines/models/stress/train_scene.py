r"""The FE scene of a whole planetary train at one position (``model = "train"``): sun, n planets, ring, with
three-tooth bodies at every mesh; the generalisation of the twin scene (:func:`pipelines.models.stress.scene.twin_scene`)
to n planets, built from the same pieces (:func:`pipelines.models.stress.scene.mesh_interface`, :mod:`mesher.placement`).

Frame, meshes and angles are those of the train's loaded TCA (:mod:`pipelines.models.trains.geometry`): the
carrier frame :math:`S_f`, planet i at :math:`\theta_i = 2\pi i/n`, its sun mesh and ring mesh each a
:class:`tca.pair.gear_pair.GearPair` in its own pair frame (:attr:`MeshSite.frame`), the sun at
:math:`\psi_1` (its angle relative to the carrier), so that the sun's driver angle in the sun mesh of planet i
is :math:`\phi_i = \psi_1 - \theta_i`.

Placement (no load). Planet i is turned until it touches the sun, :math:`\phi_{2,i}` from the sun mesh's TCA
at :math:`\phi_i` (:func:`tca.pair.te.mesh_contact`); in its ring mesh it then drives at
:math:`\phi'_i = \phi_{2,i} + \pi + \pi/N_2`. One ring serves every planet: with its nominal angle
:math:`(N_2/N_3)\phi'^{0}_i` in pair frame i (:math:`\phi'^{0}_i = (N_1/N_2)\phi_i + \pi + \pi/N_2`, the same
ring for every planet when :math:`(N_1 + N_3)/n` is an integer, Eq. 1.3) and its common turn
:math:`\delta_3`, planet i touches the ring at :math:`\delta_{3,i} = \phi_{3,i} - (N_2/N_3)\phi'^{0}_i`
(:math:`\phi_{3,i}` from the ring mesh's TCA at :math:`\phi'_i`). The ring is placed at
:math:`\delta_3 = \max_i \delta_{3,i}` (the planet that leads touches; the others keep their backlash at the ring,
as the twin's member that is behind). The errors that are small rigid offsets of a body (pin errors, run-outs, centre
errors; :func:`pipelines.models.trains.geometry.offsets` at :math:`\psi_1`) translate the body's parts in
:math:`S_f`: the meshes' initial gaps change by :math:`\mp\mathbf n\cdot\mathbf e` (Eq. T4 of
:mod:`pipelines.models.trains.model`), which the FE contact takes as it takes any initial gap (linear, small
displacements).

Bodies and supports (the train LTCA's conventions: torque on the sun, ring held, carrier output). The carrier is
the frame: each planet is rigid on its rim, tied to a reference node on its pin (the pin offset included) with only
its rotation about its own axis free; the sun is rigid on its rim with its rotation free under the torque
:math:`T` (and its two translations free where it floats); the ring is held on its rim. The carrier's output torque
is the moment of the planets' pin reactions about the sun axis. Holding the carrier and loading the sun is, for the
loads, the same problem as holding the sun's rotation and loading a free carrier with the output torque: the two
differ by the train's rigid mechanism (the whole train turning with the ring held), which carries no load.
The ring's reaction torque must be :math:`T N_3/N_1`.

Sizes. Each mesh is sized as a twin mesh (:func:`pipelines.models.stress.scene.mesh_interface`): by Hertz's contact
of the planet's load at its TCA point, or by the loaded estimate of the mesh (``[mesh] sizing = "loaded"``), with
the planet's load taken from the train LTCA's share at the same position (``shares``; 1/n without it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from mesher import ReferencePoint
from mesher.placement import Pose
from fem.material import Material
from tca.errors import GearfeError
from tca.pair.analysis import ContactKind, TCAOptions, run_pair_tca
from tca.pair.te import MeshTE, mesh_contact
from tca.units import ARCSEC

from pipelines.models.stress.loaded import Estimator
from pipelines.models.stress.scene import Interface, Placing, Reaction, RigidBody, Scene, mesh_interface
from pipelines.models.stress.sizing import SizeRules
from pipelines.models.trains.geometry import TrainErrors, TrainLayout, offsets, single_layout

__all__ = ["TrainSetting", "train_scene", "planet_body", "SUN_FREE"]

SUN_FREE = {"fixed": ("rz",), "floating": ("ux", "uy", "rz")}  # the sun reference node's free DOFs


@dataclass(frozen=True)
class TrainSetting:
    """What places and loads a train scene: its gears and planets, errors (offsets), sun axis, torque on the sun [N mm],
    the sun's angle relative to the carrier psi1 [rad], TCA options, and optionally the planets' shares of the sun
    torque from the train LTCA (sizes of the meshes)."""

    sun: object  # Gear
    planet: object
    ring: object
    planets: int
    errors: TrainErrors
    sun_axis: str  # 'fixed' or 'floating'
    torque: float  # [N mm] on the sun
    psi1: float  # [rad]
    tca: TCAOptions = TCAOptions()
    shares: tuple = ()  # per planet, of the sun torque (LTCA); () -> 1/n


def planet_body(i: int) -> str:
    """The body name of planet i (0-based): 'planet1', 'planet2', ..."""
    return f"planet{i + 1}"


def _shift(itf: Interface, e_driver: np.ndarray, e_driven: np.ndarray) -> Interface:
    """The interface with its driver's and driven part's teeth translated by e [mm] in S_f (the contact point with
    the slave's)."""
    d = replace(itf.driver, t=itf.driver.t + e_driver)
    n = replace(itf.driven, t=itf.driven.t + e_driven)
    e_slave = e_driven if itf.slave == "driven" else e_driver
    return replace(itf, driver=d, driven=n, point=itf.point + e_slave)


def _vec3(v) -> np.ndarray:
    """A plane offset (2,) [mm] as a vector of S_f."""
    return np.array([float(v[0]), float(v[1]), 0.0])


def _loads(estimator: Estimator | None, pair, mte: MeshTE, c, torque: float):
    """The loaded estimate of one mesh carrying ``torque`` on its driven gear, or (None, reason)."""
    if estimator is None:
        return None, None
    try:
        lines = estimator.lines(pair, mte, c.phi1, c.params)
        return estimator.load(pair, lines, torque), None
    except GearfeError as exc:
        return None, str(exc)


def train_scene(s: TrainSetting, rules: SizeRules, mat: Material, estimator: Estimator | None = None) -> Scene:
    """Sun, ``s.planets`` planets and ring at psi1 (module docstring): 3 n + 3 parts, 2 n interfaces."""
    lay: TrainLayout = single_layout(s.sun, s.planet, s.ring, s.planets)
    n = s.planets
    N1, N2, N3 = lay.teeth
    key12 = next(site.key for site in lay.sites if site.kind == "sun")
    key23 = next(site.key for site in lay.sites if site.kind == "ring")
    p12, p23 = lay.pairs[key12], lay.pairs[key23]
    r12, r23 = run_pair_tca(p12, s.tca), run_pair_tca(p23, s.tca)
    m12, m23 = MeshTE.from_result(r12), MeshTE.from_result(r23)
    off = offsets(lay, s.errors, s.psi1)
    frames = {(site.planet, site.kind): site.frame for site in lay.sites}
    per = []
    for i in range(n):
        ph = s.psi1 - lay.theta[i]
        c12 = mesh_contact(r12, ph)
        ph2p = c12.phi2 + math.pi + math.pi / N2
        c23 = mesh_contact(r23, ph2p)
        nominal3 = (N2 / N3) * ((N1 / N2) * ph + math.pi + math.pi / N2)
        per.append((ph, c12, c23, nominal3, c23.phi2 - nominal3))
    d3 = max(p[4] for p in per)
    lead = int(np.argmax([p[4] for p in per]))
    shares = tuple(s.shares) if s.shares else (1.0 / n,) * n
    parts, itfs, planets, failed = [], [], [], []
    rigid = {}
    for i, (ph, c12, c23, nominal3, d3i) in enumerate(per):
        body = planet_body(i)
        T_i = max(shares[i], 0.05 / n) * s.torque  # sized for at least a twentieth of an equal share
        T_planet, T_ring = T_i * N2 / N1, T_i * N3 / N1
        load12, f12 = _loads(estimator, p12, m12, c12, T_planet)
        c23r = replace(c23, phi2=nominal3 + d3)  # the ring at its common turn: planet i keeps (d3 - d3i) of backlash
        load23, f23 = _loads(estimator, p23, m23, c23, T_ring)
        failed += [f for f in (f12, f23) if f]
        member = f"p{i + 1}"
        s_itf = mesh_interface(Placing("sun-planet", member, ("sun", body), (member, "sun"), "driven",
                                       frames[(i, "sun")]), p12, c12, T_planet, rules, mat, load12)
        r_itf = mesh_interface(Placing("planet-ring", member, (body, "ring"), ("ring", member), "driver",
                                       frames[(i, "ring")]), p23, c23r, T_ring, rules, mat, load23)
        e_p = _vec3(off["planets"][i])
        s_itf = _shift(s_itf, _vec3(off["sun"]), e_p)
        r_itf = _shift(r_itf, e_p, _vec3(off["ring"]))
        itfs += [s_itf, r_itf]
        parts += [s_itf.driver, s_itf.driven, r_itf.driver, r_itf.driven]
        o = lay.planet_origin[i] + e_p
        rigid[body] = RigidBody(ReferencePoint(tuple(float(x) for x in o), tuple(float(x) for x in lay.planet_axis[i])), 0.0)
        planets.append({"planet": i + 1, "theta_deg": math.degrees(lay.theta[i]), "sun_phi_deg": math.degrees(ph),
                        "planet_phi_deg": math.degrees(c12.phi2), "te12_arcsec": c12.te / ARCSEC,
                        "te23_arcsec": c23.te / ARCSEC, "ring_backlash_um": (d3 - d3i) * lay.ring.r_p * 1e3,
                        "offset_um": [float(x) * 1e3 for x in off["planets"][i]],
                        "sun_mesh": {"kind": ContactKind.names.get(int(c12.kind), str(c12.kind)), "active_pair": c12.k,
                                     "next_pair_gap_um": c12.next_gap * 1e3},
                        "ring_mesh": {"kind": ContactKind.names.get(int(c23.kind), str(c23.kind)), "active_pair": c23.k,
                                      "next_pair_gap_um": c23.next_gap * 1e3},
                        "sized_for_share": shares[i]})
    sun_o = _vec3(off["sun"])
    rigid["sun"] = RigidBody(ReferencePoint(tuple(float(x) for x in sun_o), (0.0, 0.0, 1.0)), abs(s.torque),
                             SUN_FREE[s.sun_axis])
    info = {"psi1_deg": math.degrees(s.psi1), "phi1_deg": math.degrees(s.psi1), "sun_axis": s.sun_axis,
            "leading_planet": lead + 1, "ring_turn_arcsec": d3 / ARCSEC, "planets": planets,
            "sun_offset_um": [float(x) * 1e3 for x in off["sun"]], "ring_offset_um": [float(x) * 1e3 for x in off["ring"]],
            "loaded_estimate": {"sizing": "tca" if estimator is None or failed else "loaded",
                                **({"failed": failed[0]} if failed else {})}}
    return Scene("train", tuple(parts), tuple(itfs), "ring", rigid,
                 Reaction("ring", (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), abs(s.torque) * N3 / N1), N3 / N1, info)
