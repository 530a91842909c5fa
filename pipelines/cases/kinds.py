"""The one registry of case kinds: for every ``kind`` of case file, its reader, the commands that take it and,
for the TCA kinds, the analysis behind ``gearfe tca``.

A new kind is registered here once: a reader that checks every key of a case table (strict: unknown keys
are errors) and returns what its commands run on, the commands that accept it, and, where ``gearfe tca``
runs it, the module of its analysis (``run(case: Table, out: Path) -> summary``). The command line asks
:func:`read_case` for a file and a command; the kind is checked against the command before any work.

Readers named by ``"module:function"`` are imported when used, so reading one kind does not import the
models of the others.
"""

from __future__ import annotations

import copy
import importlib
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any, Callable, Mapping

from tca.errors import InputError

from pipelines.cases.schema import Table

__all__ = ["CaseKind", "KINDS", "kinds_for", "kind_of", "reader", "read_case", "validate_case", "analysis_module"]


@dataclass(frozen=True)
class CaseKind:
    """One kind of case file: what it describes, the reader of each command that takes it, its TCA analysis."""

    name: str
    describes: str
    readers: Mapping[str, str]  # command -> "module:function" reading a Table (every key checked)
    analysis: str = ""  # module with run(case: Table, out: Path) -> summary, for gearfe tca
    field_names: Mapping[str, str] = field(default_factory=dict)  # tca field -> case-file key in errors
    kind_optional: bool = False  # files of this kind may leave out the kind key (mesh cases)

    @property
    def commands(self) -> tuple[str, ...]:
        return tuple(self.readers)


def _kinds(*ks: CaseKind) -> Mapping[str, CaseKind]:
    return MappingProxyType({k.name: k for k in ks})


_TCA = "pipelines.cases.validate"
_RATE = "pipelines.cases.rate"  # gearfe rate: ISO 6336 of the case's [rating]
KINDS: Mapping[str, CaseKind] = _kinds(
    # one file per pair: a pair file loads the pair for the stress commands (with a torque key), and a stress
    # file of model "pair" gives gearfe tca its pair (its load, position, mesh and FE keys checked, unused)
    CaseKind("pair", "a gear pair: gears, driver and driven, centre distance, misalignment, TCA resolution; with a "
             "torque (and optional position, [mesh], [fe], [ltca]) also a stress case",
             {"tca": f"{_TCA}:read_pair_tca", "rate": f"{_RATE}:read_pair_rate",
              "stress": "pipelines.cases.stress:read_stress_case", "run": "pipelines.cases.stress:read_stress_case",
              "compare": "pipelines.cases.stress:read_stress_case", "ltca": "pipelines.cases.ltca:read_ltca_case"},
             analysis="pipelines.analyses.pair"),
    CaseKind("planetary", "the double-helical planetary train of Part 1: gears, planets, errors of installment",
             {"tca": f"{_TCA}:read_planetary_tca", "rate": f"{_RATE}:read_planetary_rate",
              "ltca": "pipelines.cases.trains:read_planetary_ltca"}, analysis="pipelines.analyses.planetary",
             field_names={"planets.count": "planets"}),
    CaseKind("isostatic", "an isostatic planetary train of Part 3: floating members, errors, run",
             {"tca": f"{_TCA}:read_isostatic_tca", "ltca": "pipelines.cases.trains:read_isostatic_ltca",
              "stress": "pipelines.cases.stress:read_train_stress"}, analysis="pipelines.analyses.isostatic",
             field_names={"planets.count": "train.planets", "sun_axis_free": "train.sun_axis",
                          "carrier_axis_free": "train.carrier_axis", "ring_axis_free": "train.ring_axis"}),
    CaseKind("face_train", "the face-gear planetary train of Part 2: four gears, the shaper, installation angle",
             {"tca": f"{_TCA}:read_face_tca"}, analysis="pipelines.analyses.face"),
    CaseKind("stress", "a gear pair or Part 1's twin drive at a TCA position under load: mesh rules, FE settings",
             {"stress": "pipelines.cases.stress:read_stress_case", "run": "pipelines.cases.stress:read_stress_case",
              "compare": "pipelines.cases.stress:read_stress_case", "ltca": "pipelines.cases.ltca:read_ltca_case",
              "rate": f"{_RATE}:read_stress_rate", "tca": f"{_TCA}:read_stress_tca"}, analysis="pipelines.analyses.pair"),
    CaseKind("mesh", "the hexahedral model of a gear pair at a TCA position, or of one gear",
             {"mesh": "pipelines.cases.mesh:read_mesh_table"}, kind_optional=True),
)


def kinds_for(command: str) -> tuple[str, ...]:
    """The kinds a command takes, in registry order."""
    return tuple(k.name for k in KINDS.values() if command in k.readers)


def kind_of(case: Table, command: str) -> CaseKind:
    """The registered kind of a case table that ``command`` takes; InputError naming ``kind`` otherwise."""
    accepted = kinds_for(command)
    default = next((k for k in accepted if KINDS[k].kind_optional), None)
    name = case.data.get("kind", default)
    if not isinstance(name, str) or name not in accepted:
        if isinstance(name, str) and name in KINDS:
            other = ", ".join(f"gearfe {c}" for c in KINDS[name].commands)
            why = f"a {name!r} case is read by {other}"
        else:
            why = ""
        raise InputError("kind", name, f"one of {', '.join(repr(k) for k in accepted)} for gearfe {command}", why)
    return KINDS[name]


def reader(kind: CaseKind, command: str) -> Callable[[Table], Any]:
    """The reader function of a kind for a command."""
    mod, fn = kind.readers[command].split(":")
    return getattr(importlib.import_module(mod), fn)


def _renamed(kind: CaseKind, e: InputError) -> InputError:
    new = kind.field_names.get(e.field)
    return e if new is None else InputError(new, e.value, e.valid, e.why)


def validate_case(case: Table, command: str = "tca") -> CaseKind:
    """Read every key of a case for a command on a copy (the table is left untouched); returns its kind."""
    kind = kind_of(case, command)
    t = Table(copy.deepcopy(case.data), case.path)
    read_checked(t, kind, command)
    return kind


def read_checked(t: Table, kind: CaseKind, command: str):
    """Run the kind's reader on ``t`` (consumed), with the tca field names renamed to the case file's keys."""
    try:
        return reader(kind, command)(t)
    except InputError as e:
        renamed = _renamed(kind, e)
        if renamed is e:
            raise
        raise renamed from None


def read_case(path: str | Path, command: str):
    """Load a case file and read it for ``command``: (kind, what its reader returns). Every key checked here."""
    from pipelines.cases.reader import load_case

    t = load_case(path)
    kind = kind_of(t, command)
    return kind, read_checked(t, kind, command)


def analysis_module(kind: CaseKind):
    """The module of a kind's TCA analysis (``run(case, out) -> summary``)."""
    if not kind.analysis:
        raise InputError("kind", kind.name, f"a kind that gearfe tca analyses: {', '.join(kinds_for('tca'))}")
    return importlib.import_module(kind.analysis)
