"""A shipped case with overrides: the one helper every test uses to vary a case of pipelines/cases.

``overrides`` maps dotted keys to values (``{"mesh.refine": 0.3, "position": None}``: ``[mesh] refine = 0.3``,
``position`` deleted); a table value replaces the table unless ``merge`` names it.
"""

from __future__ import annotations

import copy
from pathlib import Path

from pipelines.cases.reader import CASES_DIR, load_case
from pipelines.cases.schema import Table

from tests.support.tomlw import dumps

__all__ = ["CASES_DIR", "shipped_data", "shipped_table", "write_case"]


def _path(name: str) -> Path:
    p = Path(name)
    return p if p.suffix == ".toml" and p.is_file() else CASES_DIR / (name if name.endswith(".toml") else f"{name}.toml")


def shipped_data(name: str, overrides: dict | None = None, **more) -> dict:
    """A deep copy of a shipped case's data with dotted-key overrides (None deletes a key)."""
    d = copy.deepcopy(load_case(_path(name)).data)
    for key, value in {**(overrides or {}), **more}.items():
        *path, last = key.split(".")
        t = d
        for p in path:
            t = t.setdefault(p, {})
        if value is None:
            t.pop(last, None)
        else:
            t[last] = copy.deepcopy(value)
    return d


def shipped_table(name: str, overrides: dict | None = None, **more) -> Table:
    """:func:`shipped_data` as a strict case table, ready for a reader."""
    return Table(shipped_data(name, overrides, **more), "", _path(name))


def write_case(folder: Path, name: str, data: dict) -> Path:
    """Write case data as ``folder/name.toml``; returns the path."""
    p = Path(folder) / f"{name}.toml"
    p.write_text(dumps(data) + "\n")
    return p
