r"""The loaded TCA of a train over a carrier revolution: positions, the coupled solve at each, shares and K_γ.

Positions. :math:`\psi_1` (the sun's angle relative to the carrier, :mod:`pipelines.models.trains.geometry`)
runs over ``carrier_revolutions`` revolutions of the carrier, P positions per mesh cycle (one sun pitch
:math:`2\pi/N_1` of :math:`\psi_1`): :math:`N_3` cycles per carrier revolution, so
:math:`\psi_{1,j} = 2\pi j/(P N_1)`, :math:`j = 0 \dots P N_3 c - 1`. The fixed-frame angles: carrier
:math:`\phi_c = m_{c1}\psi_1/(1 - m_{c1})`, sun :math:`\phi_1 = \psi_1 + \phi_c`.

Conventions (stated in ``summary.json``). The torque T acts on the sun (positive: the sun drives in its
positive sense), the ring is held, the carrier is the output. Planet i's share of the sun mesh is the part of
the sun torque it carries, :math:`s_i = \sum_{s\in i} F_s\,((\mathbf x_s\times\mathbf n_s)\cdot\mathbf e_z) / T`
(summed over its members: a twin is one planet); its ring share the same for the ring's reaction torque. The
planet load-sharing factor of ISO 6336-1 / AGMA 6123 over the run is

.. math:: K_\gamma = \max_j\; n\,\max_i s_{i,j},                                           \qquad (T5)

and for a twin, per member k, :math:`K_{\gamma,\text{members}} = \max_j 2n\max_{i,k} s_{ik,j}`. The loaded
TE of the train is the carrier's angle minus its kinematic angle at the given sun angle,
:math:`\Delta\phi_c = -m_{c1}\,\omega_1` (:math:`\omega_1` the sun's rotation in the solve, relative to the
carrier with the ring at its nominal place; negative: the carrier lags). The sun centre path (where the sun
floats or sits on a support) is its translation turned into the fixed frame, :math:`R(\phi_c)\,\mathbf t_1`.
A planet that carries no load at a position is reported (``unloaded``), not an error.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from tca.units import ARCSEC

from pipelines.models.trains.geometry import TrainErrors, rot2
from pipelines.models.trains.model import TrainModel
from pipelines.models.trains.solver import SolveOptions, solve_train

__all__ = ["TrainRun", "train_positions", "solve_run", "CONVENTIONS"]

CONVENTIONS = {
    "torque": "on the sun, positive in the sun's positive sense; ring held; carrier output",
    "planet_share": "planet's part of the sun torque (sun mesh) or of the ring's reaction torque (ring mesh), "
                    "summed over its members",
    "k_gamma": "max over the positions of n x the largest planet share of the sun mesh (ISO 6336-1, AGMA 6123)",
    "k_gamma_members": "max over the positions of (n members) x the largest member share of the sun mesh",
    "loaded_te": "carrier angle minus its kinematic angle at the given sun angle [arcsec] (negative: the carrier lags)",
    "sun_center": "sun centre translation in the fixed frame [um]",
    "pin_error": "tangential along the carrier's rotation, radial outwards (Part 3, Eq. 3.12)",
}


@dataclass(frozen=True, eq=False)
class TrainRun:
    """Results of one torque over the positions (arrays over positions j; planets i; sites m of the layout)."""

    torque: float  # [N mm]
    psi1: np.ndarray  # (J,) [rad]
    carrier: np.ndarray  # (J,) φc [rad]
    sun_share: np.ndarray  # (J, n)
    ring_share: np.ndarray  # (J, n)
    member_share: np.ndarray  # (J, n, members) of the sun mesh
    te: np.ndarray  # (J,) loaded TE Δφc [rad]
    sun_center: np.ndarray  # (J, 2) [mm] fixed frame (zeros when held rigidly)
    peak_pressure: np.ndarray  # (J, sites) [MPa]
    mesh_force: np.ndarray  # (J, sites) total normal force [N]
    solve_s: float
    build_slices_s: float

    @property
    def planets(self) -> int:
        return self.sun_share.shape[1]

    @property
    def k_gamma(self) -> float:
        """Eq. (T5)."""
        return float(self.planets * self.sun_share.max())

    @property
    def k_gamma_members(self) -> float:
        return float(self.member_share.shape[1] * self.member_share.shape[2] * self.member_share.max())

    @property
    def unloaded(self) -> list:
        """(planet 1-based, number of positions) of planets without load at some positions."""
        z = (self.sun_share <= 1e-9).sum(0)
        return [(i + 1, int(k)) for i, k in enumerate(z) if k]

    def shares_summary(self) -> list:
        """Per planet: min, mean, max of its sun-mesh and ring-mesh shares."""
        out = []
        for i in range(self.planets):
            s, r = self.sun_share[:, i], self.ring_share[:, i]
            out.append({"planet": i + 1, "sun_min": float(s.min()), "sun_mean": float(s.mean()),
                        "sun_max": float(s.max()), "ring_min": float(r.min()), "ring_mean": float(r.mean()),
                        "ring_max": float(r.max())})
        return out


def train_positions(model: TrainModel) -> np.ndarray:
    """ψ1 [rad] of the run (module docstring)."""
    N1, _, N3 = model.layout.teeth
    P = model.opts.positions_per_cycle
    J = int(round(P * N3 * model.opts.carrier_revolutions))
    return 2 * math.pi * np.arange(max(J, 1)) / (P * N1)


def solve_run(model: TrainModel, errors: TrainErrors, torque: float, psi1=None, bar=None,
              opts: SolveOptions = SolveOptions()) -> TrainRun:
    """Solve the train at every position ψ1 (default :func:`train_positions`) under a torque T [N mm] on the sun."""
    lay = model.layout
    psi1 = train_positions(model) if psi1 is None else np.asarray(psi1, float).reshape(-1)
    n, members = lay.planets, len(lay.members)
    mi = {k: j for j, k in enumerate(lay.members)}
    J, S = len(psi1), len(lay.sites)
    sun_sh, ring_sh = np.zeros((J, n)), np.zeros((J, n))
    mem = np.zeros((J, n, members))
    te, centre = np.zeros(J), np.zeros((J, 2))
    peak, force = np.zeros((J, S)), np.zeros((J, S))
    rigid = model.rigid(torque)
    mc = lay.carrier_ratio
    phic = mc * psi1 / (1.0 - mc)
    d = model.dof
    warm = None
    t_build = t_solve = 0.0
    for j, ps in enumerate(psi1):
        t0 = time.perf_counter()
        blocks, rows, _ = model.blocks(float(ps), errors, torque)
        t1 = time.perf_counter()
        sol = solve_train(blocks, rigid, model.opts.material, model.local, warm, opts)
        t_solve += time.perf_counter() - t1
        t_build += t1 - t0
        warm = sol.warm()
        ring_total = 0.0
        for m, (site, F, r, p) in enumerate(zip(lay.sites, sol.F, rows, sol.pressure)):
            tq = float(F @ r.sun_arm)
            force[j, m] = float(F.sum())
            peak[j, m] = float(p.max()) if len(p) else 0.0
            if site.kind == "sun":
                sun_sh[j, site.planet] += tq
                mem[j, site.planet, mi[site.member]] += tq
            else:
                ring_sh[j, site.planet] += tq
                ring_total += tq
        sun_sh[j] /= torque
        mem[j] /= torque
        if ring_total != 0.0:
            ring_sh[j] /= ring_total
        te[j] = -mc * sol.q[d.sun_rot]
        if d.sun_t:
            centre[j] = rot2(phic[j]) @ sol.q[list(d.sun_t)]
        if bar is not None:
            bar(j + 1, J)
    return TrainRun(float(torque), psi1, phic, sun_sh, ring_sh, mem, te, centre, peak, force, t_solve, t_build)


def arcsec(x) -> np.ndarray:
    return np.asarray(x, float) / ARCSEC
