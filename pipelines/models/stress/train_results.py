r"""The train model's own results (``model = "train"``): each planet's share of the sun torque from the FE contact
forces, beside the train LTCA's at the same position, and the torques of the three members.

Planet share (the train LTCA's convention, :data:`pipelines.models.trains.run.CONVENTIONS`): the part of the sun
torque that planet i carries, from its sun mesh,

.. math:: s_i = \frac{\sum_{a\in i} f_a\,((\mathbf x_a - \mathbf o_1)\times\mathbf n_i)\cdot\mathbf e_z}
                     {\sum_j \sum_{a\in j} f_a\,((\mathbf x_a - \mathbf o_1)\times\mathbf n_j)\cdot\mathbf e_z},   \qquad (F1)

:math:`f_a` the FE's normal contact force at slave node a of the mesh's contact pairs (every modelled pair of teeth),
:math:`\mathbf n_i` the mesh's TCA normal (on a spur involute mesh the normal of every contact, so that the arm is the
base radius), :math:`\mathbf o_1` the sun's axis; the ring share the same with the ring mesh's forces (the part of the
ring's reaction torque). ``k_gamma_position`` is :math:`n\max_i s_i` at the position (Eq. T5 at one position).

The carrier's output torque is the moment of the planets' pin reactions about the sun axis; with the ring's reaction
and the sun's torque it closes the train's equilibrium, :math:`T + R_3 + R_c = 0` (reactions about :math:`+\mathbf e_z`) (checked: ``torque_closure``).

The train LTCA at the FE's position (:func:`ltca_at`: the same case, its ``[ltca]`` flank grid and supports) is also
the check before meshing that every planet carries load (a planet that the LTCA leaves without load would be a free
rigid body in the FE): :func:`check_loaded`.
"""

from __future__ import annotations

import math

import numpy as np

from fem.model import FEModel
from fem.result import FEResult
from fem.mesh.hexmesh import HexMesh
from tca.errors import InputError

from pipelines.models.stress.scene import Scene
from pipelines.models.stress.train_scene import planet_body
from pipelines.models.trains.geometry import rot2, single_layout
from pipelines.models.trains.model import build_train_model
from pipelines.models.trains.run import CONVENTIONS, TrainRun, solve_run

__all__ = ["ltca_at", "check_loaded", "fe_shares", "train_record", "train_psi1", "UNLOADED_SHARE"]

UNLOADED_SHARE = 1e-9  # a planet share at or below this carries no load


def train_psi1(train_case, position: int) -> float:
    """psi1 [rad] of position j of the train LTCA's run: 2 pi j / (P N1) (:func:`pipelines.models.trains.run.train_positions`)."""
    return 2 * math.pi * position / (train_case.opts.positions_per_cycle * train_case.sun.teeth)


def ltca_at(train_case, psi1: float, torque: float) -> TrainRun:
    """The train LTCA of the case at one position psi1 [rad] under the torque [N mm] on the sun."""
    tc = train_case
    model = build_train_model(single_layout(tc.sun, tc.planet, tc.ring, tc.planets), tc.opts)
    return solve_run(model, tc.errors, torque, [psi1])


def check_loaded(train_case, run: TrainRun) -> None:
    """InputError naming the planet errors when a planet carries no load at the position (module docstring)."""
    idle = [i + 1 for i in range(run.planets) if run.sun_share[0, i] <= UNLOADED_SHARE]
    if not idle:
        return
    pins = {f"planet{i + 1}": [round(p[1] * 1e3, 6), round(p[0] * 1e3, 6)] for i, p in enumerate(train_case.errors.pins)
            if p[0] or p[1]}
    raise InputError("train.planet_errors", pins or None, "errors under which every planet carries load at the FE's "
                     "position ([tangential_um, radial_um] per planet)",
                     f"planet(s) {', '.join(map(str, idle))} carry no load by the train LTCA at psi1 = "
                     f"{math.degrees(float(run.psi1[0])):.4f} deg: separated from the sun and the ring, a free body in "
                     "the FE (gearfe ltca reports such a planet as unloaded)")


def _torques(scene: Scene, mesh: HexMesh, model: FEModel, r: FEResult) -> dict:
    """(interface, member) -> torque [N mm] about the sun axis of the mesh's FE contact forces (Eq. F1)."""
    out = {}
    f = r.contact_force if r.contact_force is not None else np.zeros(mesh.n_points)
    for itf in scene.interfaces:
        group = f"{itf.name}/{itf.member}"
        nodes = [mesh.face_set_points(cp.slave) for cp in model.contacts if cp.group == group]
        nodes = np.unique(np.concatenate(nodes)) if nodes else np.zeros(0, int)
        arm = np.cross(mesh.points[nodes], itf.normal)[:, 2]
        out[(itf.name, itf.member)] = float(np.abs(f[nodes] @ arm))
    return out


def fe_shares(scene: Scene, mesh: HexMesh, model: FEModel, r: FEResult) -> tuple[np.ndarray, np.ndarray]:
    """(sun shares, ring shares) per planet from the FE contact forces (Eq. F1)."""
    tq = _torques(scene, mesh, model, r)
    n = len([i for i in scene.interfaces if i.name == "sun-planet"])
    sun = np.array([tq[("sun-planet", f"p{i + 1}")] for i in range(n)])
    ring = np.array([tq[("planet-ring", f"p{i + 1}")] for i in range(n)])
    return sun / max(sun.sum(), 1e-300), ring / max(ring.sum(), 1e-300)


def train_record(scene: Scene, mesh: HexMesh, model: FEModel, r: FEResult, ltca: TrainRun, interfaces: dict) -> dict:
    """The summary's ``train`` record: shares of the FE and of the LTCA per planet, torques, conventions."""
    sun, ring = fe_shares(scene, mesh, model, r)
    n = len(sun)
    T = scene.rigid["sun"].torque
    ring_reaction = r.support_torque("ring", (0.0, 0.0, 0.0), (0.0, 0.0, 1.0))
    carrier = sum(r.support_torque(planet_body(i), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)) for i in range(n))
    ls, lr = ltca.sun_share[0], ltca.ring_share[0]
    planets = []
    for i in range(n):
        m = f"p{i + 1}"
        s_m, r_m = interfaces["sun-planet"]["members"][m], interfaces["planet-ring"]["members"][m]
        planets.append({"planet": i + 1, "sun_share": float(sun[i]), "ring_share": float(ring[i]),
                        "ltca_sun_share": float(ls[i]), "ltca_ring_share": float(lr[i]),
                        "sun_share_minus_ltca": float(sun[i] - ls[i]), "ring_share_minus_ltca": float(ring[i] - lr[i]),
                        "sun_mesh_force_n": s_m["force_n"], "ring_mesh_force_n": r_m["force_n"],
                        "sun_mesh_peak_pressure_mpa": s_m["max_contact_pressure_mpa"],
                        "ring_mesh_peak_pressure_mpa": r_m["max_contact_pressure_mpa"],
                        "ltca_sun_mesh_peak_pressure_mpa": float(ltca.peak_pressure[0, 2 * i]),
                        "ltca_ring_mesh_peak_pressure_mpa": float(ltca.peak_pressure[0, 2 * i + 1])})
    motion = r.rigid_motion.get("sun")
    t1 = np.asarray(motion[0][:2], float) if motion is not None else np.zeros(2)
    centre = [float(x) * 1e3 for x in rot2(float(ltca.carrier[0])) @ t1]  # fixed frame, as the LTCA's sun centre
    return {"planets": planets, "psi1_deg": float(math.degrees(ltca.psi1[0])),
            "k_gamma_position": float(n * sun.max()), "ltca_k_gamma_position": float(n * ls.max()),
            "max_share_difference": float(max(np.abs(sun - ls).max(), np.abs(ring - lr).max())),
            "sun_torque_nm": T * 1e-3, "ring_reaction_torque_nm": ring_reaction * 1e-3,
            "carrier_torque_nm": carrier * 1e-3,
            "torque_closure": float(abs(T + ring_reaction + carrier) / T),
            "sun_center_um": centre, "ltca_sun_center_um": [float(x) * 1e3 for x in ltca.sun_center[0]],
            "unloaded_planets": [i + 1 for i in range(n) if sun[i] <= UNLOADED_SHARE],
            "conventions": {**CONVENTIONS, "fe_carrier": "the carrier is the frame (held); its output torque is the "
                            "moment of the planets' pin reactions about the sun axis",
                            "fe_share": "Eq. F1 of pipelines.models.stress.train_results: moments of the FE's nodal "
                                        "contact forces about the sun axis"}}
