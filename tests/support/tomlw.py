"""A minimal TOML writer for the hostile-input tests: tables, arrays of tables, scalars, lists of scalars."""

from __future__ import annotations

import json
import math

__all__ = ["dumps"]


def _val(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_inline(x) for x in v) + "]"
    if isinstance(v, dict):
        return _inline(v)
    raise TypeError(type(v))


def _inline(v) -> str:
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {_inline(x)}" for k, x in v.items()) + "}"
    return _val(v)


def _is_aot(v) -> bool:
    return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)


def dumps(d: dict, prefix: str = "") -> str:
    """TOML text of a dict (keys quoted, so any key text survives)."""
    lines = [f"{json.dumps(k)} = {_val(v)}" for k, v in d.items() if not isinstance(v, dict) and not _is_aot(v)]
    for k, v in d.items():
        name = f"{prefix}{json.dumps(k)}"
        if isinstance(v, dict):
            lines += ["", f"[{name}]", dumps(v, name + ".")]
        elif _is_aot(v):
            for x in v:
                lines += ["", f"[[{name}]]", dumps(x, name + ".")]
    return "\n".join(lines)
