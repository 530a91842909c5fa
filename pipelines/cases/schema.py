"""Strict reading of TOML case files: every key is named, typed, range-checked; unknown keys are errors.

Usage::

    t = Table(tomllib.load(fh), "case.toml")
    teeth = t.get("teeth", int, lo=3)
    face = t.get("face_width_mm", float, lo=0.0, lo_open=True)
    t.done()        # raises InputError naming any key that was not read
"""

from __future__ import annotations

import math
from typing import Any, Iterable

from tca.errors import InputError

__all__ = ["Table", "REQUIRED"]


class _Required:
    def __repr__(self):
        return "REQUIRED"


REQUIRED: Any = _Required()


class Table:
    """A TOML table being read; remembers which keys were used."""

    def __init__(self, data: dict, path: str = "", source=None):
        if not isinstance(data, dict):
            raise InputError(path or "<root>", data, "a TOML table")
        self.data, self.path, self._seen = data, path, set()
        self.source = source  # the file the table was read from (a Path), None for tables built in code

    def _key(self, key: str) -> str:
        return f"{self.path}.{key}" if self.path else key

    def has(self, key: str) -> bool:
        return key in self.data

    def get(
        self,
        key: str,
        kind: type = float,
        default: Any = REQUIRED,
        *,
        lo: float | None = None,
        hi: float | None = None,
        lo_open: bool = False,
        hi_open: bool = False,
        choices: Iterable | None = None,
    ) -> Any:
        """Read a scalar (or list when ``kind`` is ``list``) with type and range checks."""
        self._seen.add(key)
        name = self._key(key)
        if key not in self.data:
            if default is REQUIRED:
                raise InputError(name, None, _describe(kind, lo, hi, lo_open, hi_open, choices), "missing key")
            return default
        v = self.data[key]
        if kind is float:
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                raise InputError(name, v, "a number")
            v = float(v)
            if not math.isfinite(v):
                raise InputError(name, v, "a finite number")
        elif kind is int:
            if isinstance(v, bool) or not isinstance(v, int):
                raise InputError(name, v, "an integer")
        elif kind is bool:
            if not isinstance(v, bool):
                raise InputError(name, v, "true or false")
        elif kind is str:
            if not isinstance(v, str):
                raise InputError(name, v, "a string")
        elif kind is list:
            if not isinstance(v, list):
                raise InputError(name, v, "a list")
        if choices is not None and v not in tuple(choices):
            raise InputError(name, v, "one of " + ", ".join(repr(c) for c in choices))
        if lo is not None and (v < lo or (lo_open and v == lo)):
            raise InputError(name, v, _describe(kind, lo, hi, lo_open, hi_open, None))
        if hi is not None and (v > hi or (hi_open and v == hi)):
            raise InputError(name, v, _describe(kind, lo, hi, lo_open, hi_open, None))
        return v

    def table(self, key: str, required: bool = True) -> "Table | None":
        """A sub-table; None when optional and absent."""
        self._seen.add(key)
        if key not in self.data:
            if required:
                raise InputError(self._key(key), None, "a table", "missing table")
            return None
        return Table(self.data[key], self._key(key), self.source)

    def tables(self, key: str, required: bool = True) -> list["Table"]:
        """An array of tables (``[[key]]``)."""
        self._seen.add(key)
        if key not in self.data:
            if required:
                raise InputError(self._key(key), None, "an array of tables", "missing")
            return []
        v = self.data[key]
        if not isinstance(v, list):
            raise InputError(self._key(key), v, "an array of tables")
        return [Table(x, f"{self._key(key)}[{i}]", self.source) for i, x in enumerate(v)]

    def done(self) -> None:
        """Raise for keys that nobody read (typos, unsupported options)."""
        unknown = sorted(set(self.data) - self._seen)
        if unknown:
            known = ", ".join(sorted(self._seen)) or "none"
            raise InputError(self._key(unknown[0]), self.data[unknown[0]], f"a known key ({known})", "unknown key")


def _describe(kind, lo, hi, lo_open, hi_open, choices) -> str:
    if choices is not None:
        return "one of " + ", ".join(repr(c) for c in choices)
    noun = {float: "a number", int: "an integer", bool: "true or false", str: "a string", list: "a list"}.get(kind, str(kind))
    parts = []
    if lo is not None:
        parts.append(f"{'>' if lo_open else '>='} {lo:g}")
    if hi is not None:
        parts.append(f"{'<' if hi_open else '<='} {hi:g}")
    return noun + (" " + " and ".join(parts) if parts else "")
