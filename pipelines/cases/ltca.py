"""A loaded-TCA case: a stress case (``kind = "stress"``, ``model = "pair"``) with an optional ``[ltca]`` table.

Keys of ``[ltca]`` (all optional; every key is checked, unknown keys are rejected)::

    [ltca]
    positions = 100               # positions over one mesh cycle (one angular pitch of the driver)
    torques_nm = [78.0, 156.0]    # torques on the driven gear [N m]; default [torque_nm]
    profile_size_mm = 0.3         # flank grid: profile size; default 0.15 m
    axial_size_mm = 1.0           # flank grid: axial size, also the size of the body's elements; default min(0.5 m, b/14)
    slice_mm = 0.5                # length of a contact-line slice; default 0.25 m
    reach_um = 50.0               # pairs of teeth separated by more than this (TCA) are left out
    check_positions = 0           # positions also solved by the full contact FE (gearfe stress) for the check

Before any work the flank grid's build is planned (:mod:`pipelines.models.ltca.plan`: elements, DOF, memory) and
refused above ``GEARFE_MAX_MEMORY_GB``. The flank models take ``[mesh] teeth`` of the stress case (rim depth 3 m, elements of the axial size
away from the flanks) and the material and element of ``[fe]``; the full-FE check runs the stress
case itself (its ``[mesh]`` and ``[fe]``) at the checked positions.
"""

from __future__ import annotations


from tca.errors import InputError

from pipelines.cases.schema import Table
from pipelines.cases.stress import TORQUE_KEYS, check_unit_load, read_stress_case, read_unloaded_pair
from pipelines.cases.ltca_options import read_ltca_options
from pipelines.models.ltca.options import LTCAOptions
from pipelines.models.ltca.plan import check_plan
from pipelines.models.stress.case import StressCase

__all__ = ["read_ltca_case", "LOAD_KEYS", "loaded", "read_loaded_pair"]

# keys of a pair file that only the stress commands use (a pair file with any of them is read in full for gearfe tca)
LOAD_KEYS = TORQUE_KEYS + ("model", "position", "phi1_deg", "roll_deg", "mesh", "fe", "ltca")

def loaded(case: Table) -> bool:
    """Whether a case carries a load (a stress file, or a pair file with any of :data:`LOAD_KEYS`)."""
    return case.data.get("kind") == "stress" or any(case.has(k) for k in LOAD_KEYS)


def read_loaded_pair(case: Table):
    """(pair, TCA options, rating spec or None) of a stress file or a pair file with load keys for gearfe tca (consumes the table): every
    key checked (``[ltca]`` too, without its resource plan; the torque where one is given), the twin drive refused
    (its TCA is a ``planetary`` case)."""
    model = case.data.get("model", "pair")
    if model != "pair":
        raise InputError("model", model, "'pair' for gearfe tca (the twin drive's TCA is a kind = 'planetary' case)")
    if any(case.has(k) for k in TORQUE_KEYS):
        sc = read_ltca_case(case, plan=False)[0]
        return sc.pair, sc.tca, sc.rating
    lt = case.table("ltca", required=False)
    pair, tca, spec = read_unloaded_pair(case)
    if lt is not None:
        read_ltca_options(lt, 1.0)  # the default torques are the case's: none here, and none needed
    return pair, tca, spec


def read_ltca_case(case: Table, plan: bool = True) -> tuple[StressCase, LTCAOptions]:
    """The stress case and the ``[ltca]`` options of a case table; InputError on any bad key or value, and on a
    flank grid whose build does not fit in ``GEARFE_MAX_MEMORY_GB`` (:func:`pipelines.models.ltca.plan.check_plan`
    with ``[mesh] teeth``; checked again once the pairs within reach have set the teeth modelled)."""
    lt = case.table("ltca", required=False)
    sc = read_stress_case(case, ltca=False)
    if sc.model != "pair":
        raise InputError("model", sc.model, "'pair' (gearfe ltca models a gear pair; the twin drive is not supported yet)")
    opts = read_ltca_options(lt, sc.torque)
    for T in opts.torques:  # every torque of the cycle within the unit load of a stress case
        check_unit_load("ltca.torques_nm", [x * 1e-3 for x in opts.torques], T * 1e-3, T, sc.pair)
    if plan:
        check_plan(sc, opts)
    return sc, opts
