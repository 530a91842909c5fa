r"""Stress sweeps: one contact-stress run per grid point, its scalar results, loaded TE and load share through a cycle.

Used by ``gearfe sweep`` with ``task = "stress"`` (:mod:`pipelines.cli.sweep`; its plots and page through
the cycle: :mod:`pipelines.render.sweep`). Each grid point is
a stress case (:mod:`pipelines.models.stress.run`) run by :func:`run_point_stress`; its summary gets two
records computed here:

Loaded transmission error (``loaded_te``). The FE models hold the driving body still (the
driver's rim in the pair model, the sun in the twin model) and leave the driven body rigid with
only its rotation free, the torque :math:`-T` about the axis :math:`\mathbf a` about which it turns
positively in the drive. The FE rotation vector :math:`\boldsymbol\omega` of that body
(``rigid_motion``, global components) gives its elastic rotation
:math:`\delta\phi = \boldsymbol\omega\cdot\mathbf a` (negative: it lags), and

.. math::  \Delta\phi_{loaded}(\phi_1) = \Delta\phi(\phi_1) + \delta\phi,

with :math:`\Delta\phi` the unloaded TE of the TCA at the same :math:`\phi_1` (absolute, as
:mod:`tca.pair.gear_pair`: negative is a lag). Pair: the driven gear 2, :math:`\mathbf a` =
``pair.mounts()[1].axis`` (:math:`-z_f` tilted by the misalignment for an external gear),
:math:`\Delta\phi = \Delta\phi_2`. Twin: the ring, :math:`\mathbf a = -z_f`
(:func:`pipelines.models.stress.scene.twin_scene`), :math:`\Delta\phi = \Delta\phi_3` of the member that
leads. Both in arcsec.

Gap to the next pair of teeth (``tca_second_pair_gap_arcsec``, pair model): at :math:`\phi_1`, the
difference between the TE branch in contact and the next largest branch of the other tooth
pairs (:func:`tca.pair.te.mesh_contact`, ``next_gap``; a tangency-only branch tied with the pair in
contact — conjugate flanks touching outside their working areas — does not count): the rigid-body rotation the driven gear must lag by
before a second pair touches. Where a branch is the tangency of the extended surfaces (its bounded
contact was not searched because it lies below the envelope) it is an upper bound of that pair's
:math:`\Delta\phi`, so the value is a lower bound of the gap. A second pair cannot carry load while
the elastic rotation stays below this gap.

Scaling with torque: the elastic rotation is a tooth-bending part (linear in the load P) plus the
Hertz approach of the contact (:math:`\propto P^{2/3}` for a point contact, Johnson, Contact
Mechanics, section 4.2); doubling the torque multiplies it by a factor between
:math:`2^{2/3} = 1.587` and 2.
"""

from __future__ import annotations

import copy
import math
import time
from pathlib import Path

from tca.errors import InputError
from tca.pair.analysis import ARCSEC

from pipelines.cases.schema import Table
from pipelines.models.stress.results import loaded_te

__all__ = ["POSITION_KEYS", "STEP_KEY", "validate_stress", "run_point_stress", "second_pair_gap",
           "stress_scalars", "expand_positions"]

POSITION_KEYS = ("position", "phi1_deg", "roll_deg")  # keys of a stress case that choose the position
STEP_KEY = "positions.step"  # the CSV/axis column of a [positions] steps expansion

_SCALARS = ("max_von_mises_mpa", "max_contact_pressure_mpa", "contact_force_n", "contact_area_mm2",
            "max_fillet_stress_mpa", "max_fillet_von_mises_mpa", "torque_balance_error",
            "torque_balance_error_kinematic", "reaction_torque_nm", "edge_contact", "fe_edge_contact", "dofs",
            "elements", "tca_s", "mesh_s", "solve_s", "results_s", "total_s", "cpu_s")


def expand_positions(t: Table | None) -> tuple[str, list] | None:
    """The ``[positions]`` table of a sweep file -> (axis key, values), or None (cmd_sweep docstring)."""
    if t is None:
        return None
    has_steps, has_phi = t.has("steps"), t.has("phi1_deg")
    if has_steps == has_phi:
        raise InputError(f"{t.path}", sorted(t.data), "either steps (with optional start) or phi1_deg, not both")
    if has_phi:
        vals = t.get("phi1_deg", list)
        if not vals or any(isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) for v in vals):
            raise InputError(f"{t.path}.phi1_deg", vals, "a non-empty list of finite angles [deg]")
        t.done()
        return "phi1_deg", [float(v) for v in vals]
    n = t.get("steps", int, lo=1, hi=2000)
    start = t.get("start", int, 0, lo=0)
    t.done()
    return STEP_KEY, [(i, n, start) for i in range(n)]


def apply_position(case: dict, key: str, value, where: str) -> object:
    """Set a position axis value on a case dict (replacing the base's position choice); returns the CSV value."""
    for k in POSITION_KEYS:
        case.pop(k, None)
    if key != STEP_KEY:
        case[key] = value
        return value
    i, n, start = value
    t = case.get("tca", {})
    s = t.get("steps_per_cycle", 40) if isinstance(t, dict) else 40
    cycles = t.get("cycles", 2) if isinstance(t, dict) else 2
    if not isinstance(s, int) or isinstance(s, bool) or s % n:
        raise InputError("positions.steps", n, f"a divisor of tca.steps_per_cycle = {s!r} (positions on the TCA grid)")
    if not isinstance(cycles, int) or isinstance(cycles, bool) or start + s > cycles * s:
        raise InputError("positions.start", start, f"an index in [0, {(cycles - 1) * s if isinstance(cycles, int) else 0}] "
                         f"(one pitch of the TCA grid of tca.cycles = {cycles!r} x {s!r} steps)")
    case["position"] = start + i * (s // n)
    return i


def validate_stress(case: dict) -> None:
    """Parse a stress case fully (no solve) and check a position index against its TCA grid."""
    from pipelines.cases.stress import read_stress_case

    c = read_stress_case(Table(copy.deepcopy(case), ""))
    if isinstance(c.position, int) and c.phi1 is None:
        n = c.tca.cycles * c.tca.steps_per_cycle + 1
        if not -n <= c.position < n:
            raise InputError("position", c.position, f"an index of the TCA grid in [{-n}, {n - 1}]")


def second_pair_gap(tca, phi1: float) -> float:
    """Pair model: Δφ2 of the pair in contact minus the next branch at phi1 [rad] (a lower bound, module docstring),
    from the pair TCA result ``tca`` of the run."""
    from tca.pair.te import mesh_contact

    mc = mesh_contact(tca, phi1)  # next_gap: tca.pair.te (ties of conjugate flanks)
    return mc.next_gap / abs(mc.arms[1]) if mc.arms[1] else float("inf")


def run_point_stress(case_dict: dict, out: Path) -> dict:
    """Run one stress grid point into ``out`` (result.vtu); the summary with ``loaded_te`` and the next-pair gap."""
    from pipelines.cases.stress import read_stress_case
    from pipelines.models.stress.run import run_stress

    case = read_stress_case(Table(copy.deepcopy(case_dict), ""))
    run = run_stress(case, Path(out))
    s = run.summary
    s["loaded_te"] = loaded_te(case, s)
    t0 = time.perf_counter()
    gap = second_pair_gap(run.tca, math.radians(s["position"]["phi1_deg"])) / ARCSEC if case.model == "pair" else None
    s["tca_second_pair_gap_arcsec"] = gap if gap is None or math.isfinite(gap) else None
    s["gap_s"] = time.perf_counter() - t0
    return {"kind": "stress", **s, "files": ["result.vtu", "summary.json"]}


def stress_scalars(s: dict) -> dict:
    """CSV columns of a stress summary: position, TE, key stresses, times, load shares flattened."""
    pos, lt = s["position"], s["loaded_te"]
    row = {"phi1_deg": pos["phi1_deg"], "torque_nm": s["torque_nm"],
           "active_pair": pos.get("active_pair", pos.get("leading_member")),
           "te_unloaded_arcsec": lt["unloaded_te_arcsec"], "elastic_rotation_arcsec": lt["elastic_rotation_arcsec"],
           "te_loaded_arcsec": lt["loaded_te_arcsec"], "tca_second_pair_gap_arcsec": s.get("tca_second_pair_gap_arcsec")}
    row.update({k: s.get(k) for k in _SCALARS})
    for itf, sh in s["load_share"].items():
        for m, v in sh["members"].items():
            row[f"share.{itf}.member.{m}"] = v
        for name, v in sh["teeth"].items():
            row[f"share.{itf}.teeth.{name}"] = v
    return row
