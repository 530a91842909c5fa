"""Readers of the TCA kinds for :mod:`pipelines.cases.kinds`: every key, type, range, unknown key and geometry
check of a whole case, before any work.

``gearfe tca`` (and each ``task = "tca"`` grid point of ``gearfe sweep``) runs them on a copy of the case
first (:func:`pipelines.cases.kinds.validate_case`), so a typo in the last table or an impossible train is
reported in one line before any solve starts (the analyses read the same keys again as they run).
"""

from __future__ import annotations

from pipelines.cases.rating import read_rating, train_names
from pipelines.cases.schema import Table

__all__ = ["read_pair_tca", "read_stress_tca", "read_planetary_tca", "read_isostatic_tca", "read_face_tca", "validate_case"]


def _header(t: Table) -> None:
    t.get("kind", str)
    t.get("title", str, "")


def read_pair_tca(t: Table) -> None:
    """Every key of a ``kind = "pair"`` case (consumes ``t``)."""
    from pipelines.cases.ltca import loaded
    from pipelines.cases.reader import read_gears, read_pair, read_tca_options

    if loaded(t):  # a pair file with a load: every key as the stress commands read them
        return read_stress_tca(t)
    _header(t)
    pair, _, _ = read_pair(t, read_gears(t))
    read_tca_options(t.table("tca", required=False))
    read_rating(t.table("rating", required=False), (pair.gear1.name, pair.gear2.name), case_has_torque=False)  # ISO 6336
    t.done()


def read_stress_tca(t: Table) -> None:
    """Every key of a ``kind = "stress"`` case for gearfe tca (consumes ``t``): a pair model (the twin drive's TCA is
    a ``kind = "planetary"`` case); the load, position, mesh and FE keys are checked and not used."""
    from pipelines.cases.ltca import read_loaded_pair

    read_loaded_pair(t)
    t.done()


def read_planetary_tca(t: Table) -> None:
    """Every key of a ``kind = "planetary"`` case (consumes ``t``)."""
    from pipelines.cases.planetary import read_installment, read_regulation_options, read_train
    from pipelines.cases.reader import read_tca_options

    _header(t)
    train = read_train(t)
    read_installment(t.table("installment", required=False), train.planets)
    read_regulation_options(t.table("regulation", required=False))
    read_tca_options(t.table("tca", required=False))
    read_rating(t.table("rating", required=False), train_names(train), case_has_torque=False)  # ISO 6336
    t.done()


def read_isostatic_tca(t: Table) -> None:
    """Every key of a ``kind = "isostatic"`` case, and the mobility of its train (consumes ``t``)."""
    from tca.isostatic.analysis import check_mobility

    from pipelines.cases.isostatic import read_run, read_solver, read_train

    _header(t)
    train = read_train(t)
    read_run(t, train)
    read_solver(t)
    check_mobility(train)
    t.done()


def read_face_tca(t: Table) -> None:
    """Every key of a ``kind = "face_train"`` case (consumes ``t``)."""
    from pipelines.cases.face import read_face_train

    _header(t)
    read_face_train(t)
    t.done()


def validate_case(case: Table) -> str:
    """Read every key of a TCA case (a strict Table, left untouched); returns its kind's name."""
    from pipelines.cases.kinds import validate_case as validate

    return validate(case, "tca").name
