"""The ``[ltca]`` table of a pair case: :func:`read_ltca_options` (keys in docs/cases.md).

It sits below the stress and ltca readers (:mod:`pipelines.cases.stress` checks an ``[ltca]`` table that a
``gearfe stress`` or ``gearfe tca`` run leaves unused; :mod:`pipelines.cases.ltca` reads it for ``gearfe ltca``).
"""

from __future__ import annotations

from tca.errors import InputError

from pipelines.cases.schema import Table
from pipelines.models.ltca.options import LOCAL, LTCAOptions

__all__ = ["read_ltca_options", "read_torques", "read_flank_grid_keys"]


def read_torques(t: Table, torque: float) -> tuple[float, ...]:
    """``[ltca] torques_nm`` [N m] as torques [N mm]; ``(torque,)`` [N mm] when the table has none."""
    tq = t.get("torques_nm", list, None)
    if tq is None:
        return (torque,)
    if not tq or any(isinstance(x, bool) or not isinstance(x, (int, float)) or not (0 < x <= 1e7) for x in tq):
        raise InputError("ltca.torques_nm", tq, "a non-empty list of torques in (0, 1e7] N m")
    return tuple(float(x) * 1e3 for x in tq)


def read_flank_grid_keys(t: Table) -> dict:
    """The flank grid keys of an ``[ltca]`` table, shared by the pair and train readers: profile_size, axial_size,
    slice [mm] (None: the default grid) and reach [mm] (read in µm)."""
    pos = dict(lo=0.0, lo_open=True, hi=100.0)
    return dict(profile_size=t.get("profile_size_mm", float, None, **pos),
                axial_size=t.get("axial_size_mm", float, None, **pos),
                slice=t.get("slice_mm", float, None, **pos),
                reach=t.get("reach_um", float, 50.0, lo=0.0, lo_open=True, hi=5000.0) * 1e-3)


def read_ltca_options(t: Table | None, torque: float) -> LTCAOptions:
    """The :class:`LTCAOptions` of an ``[ltca]`` table (module docstring); ``torque`` [N mm] the default torque."""
    if t is None:
        return LTCAOptions(torques=(torque,))
    torques = read_torques(t, torque)
    o = LTCAOptions(
        positions=t.get("positions", int, 100, lo=1, hi=100000),
        torques=torques,
        **read_flank_grid_keys(t),
        check_positions=t.get("check_positions", int, 0, lo=0, hi=100),
        local=t.get("local", str, "strip", choices=LOCAL),
    )
    t.done()
    return o
