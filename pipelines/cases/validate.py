"""Read a whole TCA case before any work: every key, type, range, unknown key and geometry check.

``gearfe tca`` (and each ``task = "tca"`` grid point of ``gearfe sweep``) runs :func:`validate_case`
on a copy of the case first, so a typo in the last table or an impossible train is reported in
one line before any solve starts (the analyses read the same keys again as they run). Errors
raised by the ``tca`` package name its own fields (``planets.count``); they are renamed here to
the keys of the case file (``train.planets``).
"""

from __future__ import annotations

import copy

from tca.errors import InputError

from pipelines.cases.schema import Table

__all__ = ["validate_case", "KINDS", "FIELD_NAMES"]

KINDS = ("pair", "planetary", "isostatic", "face_train")

# tca field -> case-file key, per case kind
FIELD_NAMES = {
    "isostatic": {"planets.count": "train.planets", "sun_axis_free": "train.sun_axis",
                  "carrier_axis_free": "train.carrier_axis", "ring_axis_free": "train.ring_axis"},
    "planetary": {"planets.count": "planets"},
}


def validate_case(case: Table) -> str:
    """Read every key of a TCA case (a strict Table, left untouched); returns its kind."""
    t = Table(copy.deepcopy(case.data), case.path)
    kind = t.get("kind", str, choices=KINDS)
    t.get("title", str, "")
    try:
        _READERS[kind](t)
    except InputError as e:
        new = FIELD_NAMES.get(kind, {}).get(e.field)
        if new is None:
            raise
        raise InputError(new, e.value, e.valid, e.why) from None
    t.done()
    return kind


def _pair(t: Table) -> None:
    from pipelines.cases.reader import read_gears, read_pair, read_tca_options

    read_pair(t, read_gears(t))
    read_tca_options(t.table("tca", required=False))


def _planetary(t: Table) -> None:
    from pipelines.cases.planetary import read_installment, read_train
    from pipelines.cases.reader import read_tca_options

    train = read_train(t)
    read_installment(t.table("installment", required=False), train.planets)
    rt = t.table("regulation", required=False)
    if rt is not None:  # the keys of pipelines.analyses.planetary
        rt.get("tol_arcsec", float, 1e-3, lo=1e-6, hi=10.0)
        rt.get("max_iterations", int, 12, lo=2, hi=50)
        rt.done()
    read_tca_options(t.table("tca", required=False))


def _isostatic(t: Table) -> None:
    from tca.isostatic.analysis import check_mobility

    from pipelines.cases.isostatic import read_run, read_solver, read_train

    train = read_train(t)
    read_run(t, train)
    read_solver(t)
    check_mobility(train)


def _face(t: Table) -> None:
    from pipelines.cases.face import read_face_train

    read_face_train(t)


_READERS = {"pair": _pair, "planetary": _planetary, "isostatic": _isostatic, "face_train": _face}
