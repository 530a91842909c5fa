r"""Memory plan of a train's loaded TCA, from the flank grid before anything is built.

The train condenses four flank models, one after the other (:mod:`pipelines.models.trains.model`): the sun's +1
flank, the planet's −1 and +1 flanks and the ring's −1 flank (a twin's member b is member a's mirror image: no
build). Body k's build peaks at :math:`M_k` (Eq. P2 of :mod:`pipelines.models.ltca.plan`: the sparse
factorization, the dense compliance and a block of right-hand sides, for :math:`T` modelled teeth and the flank
grid :math:`h_u, h_z`) and keeps its dense compliance, :math:`8 m_k^2` bytes (:math:`m_k` flank nodes, Eq. P1).
The train's peak is bounded by

.. math:: M_\text{train} = M_0 + \max_k M_k + \sum_k 8 m_k^2                                       \qquad (P3)

with :math:`M_0` = 0.3 GB for the process itself (interpreter, libraries, the meshes' TCAs and slices): the peak
resident memory measured for the shipped trains at default grids, 0.81 GB (``part3_indexing``), 1.07 GB
(``part1_planetary_regulation``) and 1.14 GB (``part1_twin_dgamma``), was 0.29, 0.19 and 0.26 GB above
:math:`\max_k M_k + \sum_k 8 m_k^2` (0.52, 0.88 and 0.88 GB).

checked against ``GEARFE_MAX_MEMORY_GB`` (:func:`pipelines.models.stress.model.memory_limit_gb`) when the case is
read, before any work: a plan above the limit is bad input naming the grid key that made it large (the finer of
``ltca.profile_size_mm`` and ``ltca.axial_size_mm`` relative to their defaults, else ``ltca.teeth``). The build may
model more teeth than ``ltca.teeth`` where the pairs within reach need them; the plan uses ``ltca.teeth``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from tca.errors import InputError

from pipelines.models.ltca.plan import gear_plan, grid_blame
from pipelines.models.stress.model import memory_limit_gb
from pipelines.models.trains.options import TrainOptions

__all__ = ["TrainPlan", "plan_train", "check_train_plan", "PROCESS_GB"]

PROCESS_GB = 0.3  # M_0 of Eq. (P3), from the measured peaks (module docstring)


@dataclass(frozen=True)
class TrainPlan:
    """Per flank model (sun +1, planet −1, planet +1, ring −1): flank nodes, DOF, build peak [GB]; the train's
    peak (P3) [GB]."""

    flank_nodes: tuple
    dofs: tuple
    build_gb: tuple
    memory_gb: float

    def summary(self) -> dict:
        return {"flank_nodes": list(self.flank_nodes), "dofs": list(self.dofs), "build_gb": list(self.build_gb),
                "memory_gb": self.memory_gb}


def plan_train(sun, planet, ring, opts: TrainOptions) -> TrainPlan:
    """Eq. (P3) for the train's gears and its [ltca] flank grid."""
    hu, hz, _ = opts.sizes(sun.module, min(g.face_width for g in (sun, planet, ring)))
    per = [gear_plan(g, opts.teeth, hu, hz) for g in (sun, planet, planet, ring)]
    kept = sum(8e-9 * p[0] ** 2 for p in per)
    return TrainPlan(tuple(p[0] for p in per), tuple(p[2] for p in per), tuple(p[3] for p in per),
                     PROCESS_GB + max(p[3] for p in per) + kept)


def check_train_plan(sun, planet, ring, opts: TrainOptions, limit_gb: float | None = None) -> TrainPlan:
    """The plan, or an InputError naming the [ltca] key that made it too large (module docstring)."""
    plan = plan_train(sun, planet, ring, opts)
    limit = memory_limit_gb() if limit_gb is None else limit_gb
    if plan.memory_gb <= limit:
        return plan
    hu0, hz0, _ = replace(opts, profile_size=None, axial_size=None).sizes(
        sun.module, min(g.face_width for g in (sun, planet, ring)))
    key, value = grid_blame(opts, hu0, hz0, ("ltca.teeth", opts.teeth))
    raise InputError(key, value, f"a flank grid whose four flank models fit in memory (limit {limit:.3g} GB, "
                     f"GEARFE_MAX_MEMORY_GB)", f"estimated {max(plan.flank_nodes):.3g} flank nodes and "
                     f"{max(plan.dofs):.3g} DOF in the largest flank model: {plan.memory_gb:.3g} GB (docs/trains.md)")
