"""Property-based: random mutations of every subcommand's case files are refused cleanly (hypothesis).

A shipped case of each subcommand is mutated in one of the ways a user gets wrong (a value of
the wrong TOML type, a required key removed, an unknown key added at any table, an encoding
other than UTF-8), written, and run through :func:`pipelines.cli.main` in-process. Each mutation
is invalid by construction (no reader takes a table or a string where it reads a number, or a
table where it reads a scalar), so the contract of docs/errors.md must hold: exit status 2, one
error line, no traceback, no files (checked by :func:`tests.hostile.test_hostile.check_refused`).
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.hostile.test_hostile import base_data, check_refused
from tests.support.tomlw import dumps

# subcommand -> (shipped case, keys that must be present)
BASES = {
    "tca": ("part1_sun_planet", ("kind", "driver", "driven", "gears")),
    "sweep": ("sweep_part1_misalignment", ("axes", "base")),
    "mesh": ("mesh_part1_sun_planet", ("pair_case",)),
    "stress": ("stress_pair_small", ("model", "torque_nm", "driver", "gears")),
    "run": ("stress_pair_small", ("model", "torque_nm", "driven", "gears")),
    "compare": ("stress_pair_small", ("model", "torque_nm", "driver", "gears")),
}


def leaves(d: dict, prefix=()) -> list[tuple]:
    """Paths of the scalar values (and scalar lists) of nested tables; arrays of tables by index."""
    out = []
    for k, v in d.items():
        if isinstance(v, dict):
            out += leaves(v, prefix + (k,))
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for i, x in enumerate(v):
                out += leaves(x, prefix + (k, i))
        else:
            out.append(prefix + (k,))
    return out


def tables(d: dict, prefix=()) -> list[tuple]:
    out = [prefix]
    for k, v in d.items():
        if isinstance(v, dict):
            out += tables(v, prefix + (k,))
    return out


def at(d, path):
    for p in path:
        d = d[p]
    return d


def wrong_type(v):
    """Values of a TOML type no reader accepts in place of v."""
    if isinstance(v, bool):
        return st.sampled_from(["yes", {"x": 1}, [True]])
    if isinstance(v, (int, float)):
        return st.one_of(st.text(max_size=8), st.just({"value": 1}), st.booleans(), st.lists(st.integers(), max_size=3))
    if isinstance(v, str):
        return st.one_of(st.just({"name": v}), st.lists(st.floats(allow_nan=False), min_size=1, max_size=3))
    if isinstance(v, list):
        return st.one_of(st.just({"list": 1}), st.booleans())
    return st.just({"zz": 1})


@st.composite
def mutation(draw):
    command = draw(st.sampled_from(sorted(BASES)))
    base, required = BASES[command]
    data = base_data(base)
    how = draw(st.sampled_from(["type", "missing", "unknown", "encoding"]))
    raw = None
    if how == "type":
        path = draw(st.sampled_from([p for p in leaves(data) if p[-1] != "title"]))
        parent = at(data, path[:-1])
        parent[path[-1]] = draw(wrong_type(parent[path[-1]]))
    elif how == "missing":
        data.pop(draw(st.sampled_from(required)))
    elif how == "unknown":
        path = draw(st.sampled_from(tables(data)))
        key = "zz_" + draw(st.text("abcdefghijklmnopqrstuvwxyz_", min_size=1, max_size=8))
        at(data, path)[key] = draw(st.one_of(st.integers(), st.text(max_size=5), st.booleans()))
    text = dumps(data) + "\n"
    if how == "encoding":
        enc = draw(st.sampled_from(["utf-16", "utf-16-be", "utf-32", "latin1-comment", "cp1252-comment", "bytes"]))
        if enc.endswith("-comment"):
            raw = "# ".encode() + draw(st.sampled_from(["é", "ü", "°", "ñ"])).encode(enc.split("-")[0]) + b"\n" \
                + text.encode()
        elif enc == "bytes":
            raw = draw(st.binary(min_size=1, max_size=64)) + b"\xff\xfe\x80" + text.encode()
        else:
            raw = text.encode(enc)
    return command, text, raw


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(m=mutation())
def test_mutated_case_files_are_refused_cleanly(m, capsys):
    command, text, raw = m
    with tempfile.TemporaryDirectory() as d:
        work = Path(d)
        case = work / "case.toml"
        if raw is None:
            case.write_text(text)
        else:
            case.write_bytes(raw)
        pos = [str(case)]
        if command == "compare":
            second = work / "second.toml"
            second.write_text(dumps(base_data(BASES["compare"][0])) + "\n")
            pos.append(str(second))
        check_refused(capsys, work, [command, *pos, "--out", str(work / "out")], "")
