"""JSON of results: numpy values turned into plain Python, non-finite floats into null (JSON has no NaN)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from tca.errors import InputError

__all__ = ["to_json", "finite", "plain", "dumps", "write_json"]


def to_json(x):
    """``json.dumps`` default for numpy scalars and arrays; InputError for anything else."""
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, np.bool_):
        return bool(x)
    raise InputError("summary", type(x).__name__, "JSON-serialisable values")


def finite(x):
    """Replace non-finite floats (JSON has none) by None, recursively."""
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, dict):
        return {k: finite(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [finite(v) for v in x]
    return x


def plain(x):
    """A JSON-ready copy of x: numpy values as Python values, non-finite floats as None."""
    return finite(json.loads(json.dumps(x, default=to_json)))


def dumps(x) -> str:
    """Indented JSON text of x (numpy values allowed) with a final newline."""
    return json.dumps(x, indent=2, default=to_json) + "\n"


def write_json(x, path: str | Path) -> Path:
    """Write x as indented JSON to path; returns the path."""
    Path(path).write_text(dumps(x))
    return Path(path)
