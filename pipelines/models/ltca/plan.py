r"""Resource plan of a loaded TCA, made from the flank grid before anything is built (issue 24).

Per gear, with :math:`T` modelled teeth, the flank grid of profile size :math:`h_u` and axial size
:math:`h_z` (:meth:`pipelines.models.ltca.options.LTCAOptions.sizes`), the profile length
:math:`L_u = (h_a + h_f)\,m_n/\cos\alpha_n` (tip to root of the rack, an upper bound of the working
flank) and the face width :math:`b`:

.. math::

    m = T\,(\lceil L_u/h_u\rceil + 1)(\lceil b/h_z\rceil + 1) \quad\text{(P1, flank nodes condensed)}

The body's elements are counted by the stress model's element-count model
(:func:`pipelines.models.stress.model.part_elements`) with the ltca mesh's sizes (contact size
:math:`h_u`, axial size :math:`h_z`, body size :math:`\max(h_u, h_z)`, focus over the whole face),
:math:`N_\text{dof} = 3 \cdot 1.15\,N_e`. The peak memory of one gear's build is

.. math::

    M = M_\text{fact}(N_\text{dof}) + 8\,m^2 + 8 \cdot 128 \cdot N_\text{dof} \quad\text{[bytes] (P2)}

the sparse factorization :math:`M_\text{fact} = 0.54\,\text{GB}\,(N_\text{dof}/53\,000)^{1.21}`
(PARDISO, SPD, /work/shared/MEASURED.md: 0.54 / 2.7 / 8.2 GB at 53k / 209k / 499k DOF), the dense
compliance :math:`C` (m, m) and one block of 128 right-hand sides (:func:`fem.la.condense.influence_matrix`).
The gears are built one after the other: the plan's memory is the larger of the two.

The results of every position are streamed to ``results.csv`` and ``pressure.csv`` as they are solved;
only the rows of at most :data:`PLOT_POSITIONS` positions (and every ``results.csv`` row, one small
record per position and torque) stay in memory for the plots.

A plan above the limit (``GEARFE_MAX_MEMORY_GB``, validated by
:func:`pipelines.models.stress.model.memory_limit_gb`; default 80 % of the physical memory) is refused
before the build, naming the grid key that made it large.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tca.errors import InputError

from pipelines.models.ltca.options import LTCAOptions
from pipelines.models.stress.case import StressCase
from pipelines.models.stress.model import memory_limit_gb, part_elements

__all__ = ["LTCAPlan", "plan_ltca", "check_plan", "gear_plan", "grid_blame", "PLOT_POSITIONS"]

PLOT_POSITIONS = 400  # positions whose pressure slices are kept in memory for pressure.png
_NODES_PER_ELEMENT = 1.15  # hexahedral meshes of the mesher (pipelines.models.stress.model)
_FACT_GB, _FACT_DOF, _FACT_EXP = 0.54, 53_000.0, 1.21  # PARDISO SPD, /work/shared/MEASURED.md
_RHS_BLOCK = 128  # right-hand sides per block in fem.la.condense.influence_matrix


@dataclass(frozen=True)
class LTCAPlan:
    """The estimate of a loaded TCA's build: per gear (flank nodes, elements, DOF, peak memory [GB])."""

    teeth: int
    flank_nodes: tuple
    elements: tuple
    dofs: tuple
    memory_gb: float  # the larger gear's peak (the gears are built one after the other)

    def summary(self) -> dict:
        return {"teeth": self.teeth, "flank_nodes": list(self.flank_nodes), "elements": list(self.elements),
                "dofs": list(self.dofs), "memory_gb": self.memory_gb}


def gear_plan(gear, teeth: int, hu: float, hz: float) -> tuple[int, int, int, float]:
    """(flank nodes, elements, DOF, memory [GB]) of one gear's build (P1, P2)."""
    lu = (gear.addendum + gear.tool_addendum) * gear.module / math.cos(gear.pressure_angle)
    m = teeth * (math.ceil(lu / hu) + 1) * (math.ceil(gear.face_width / hz) + 1)
    top = max(hu, hz)
    sizes = {"coarse": top, "contact": hu, "axial": hz, "growth": 1.3}
    ne = part_elements(gear, sizes, teeth, gear.face_width)
    nd = 3.0 * _NODES_PER_ELEMENT * ne
    gb = _FACT_GB * (nd / _FACT_DOF) ** _FACT_EXP + 8e-9 * m * m + 8e-9 * _RHS_BLOCK * nd
    return int(m), int(ne), int(nd), float(gb)


def plan_ltca(case: StressCase, opts: LTCAOptions, teeth: int | None = None) -> LTCAPlan:
    """The plan of the module docstring for the case's pair (``teeth`` per gear, default ``[mesh] teeth``)."""
    pair = case.pair
    T = case.mesh.teeth if teeth is None else teeth
    m = max(pair.gear1.module, pair.gear2.module)
    hu, hz, _ = opts.sizes(m, min(pair.gear1.face_width, pair.gear2.face_width))
    per = [gear_plan(g, T, hu, hz) for g in (pair.gear1, pair.gear2)]
    return LTCAPlan(T, *(tuple(p[k] for p in per) for k in range(3)), max(p[3] for p in per))


def grid_blame(opts, hu0: float, hz0: float, fallback: tuple[str, object]) -> tuple[str, object]:
    """The [ltca] key (and its value) that made a flank grid too large: the finer of profile_size_mm and
    axial_size_mm relative to the default sizes hu0, hz0 [mm]; ``fallback`` (key, value) when both are default."""
    blame = {}
    if opts.profile_size is not None:
        blame["ltca.profile_size_mm"] = (hu0 / opts.profile_size, opts.profile_size)
    if opts.axial_size is not None:
        blame["ltca.axial_size_mm"] = (hz0 / opts.axial_size, opts.axial_size)
    if not blame:
        return fallback
    key, (_, value) = max(blame.items(), key=lambda kv: kv[1][0])
    return key, value


def check_plan(case: StressCase, opts: LTCAOptions, teeth: int | None = None, limit_gb: float | None = None) -> LTCAPlan:
    """The plan, or an InputError naming the grid key that made it too large (the finer of the profile and
    axial sizes relative to their defaults; ``mesh.teeth`` when the grid is the default one)."""
    plan = plan_ltca(case, opts, teeth)
    limit = memory_limit_gb() if limit_gb is None else limit_gb
    if plan.memory_gb <= limit:
        return plan
    pair = case.pair
    m = max(pair.gear1.module, pair.gear2.module)
    hu0, hz0, _ = LTCAOptions().sizes(m, min(pair.gear1.face_width, pair.gear2.face_width))
    key, value = grid_blame(opts, hu0, hz0, ("mesh.teeth", plan.teeth))
    raise InputError(key, value, f"a flank grid whose build fits in memory (limit {limit:.3g} GB, GEARFE_MAX_MEMORY_GB)",
                     f"estimated per gear {max(plan.flank_nodes):.3g} flank nodes condensed, {max(plan.elements):.3g} "
                     f"elements, {max(plan.dofs):.3g} DOF: {plan.memory_gb:.3g} GB")
