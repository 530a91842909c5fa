"""Every entry of the hostile corpus (tests/hostile/corpus.py) is refused cleanly, before any work.

The contract of docs/errors.md, checked in-process through :func:`pipelines.cli.main`: exit status
2, exactly one line on stderr naming the offending key or file, nothing on stdout, no traceback,
no result files and no temporary folder left, unchanged pre-existing files.
"""

from __future__ import annotations

import random
import time
import tomllib

import pytest

from pipelines.cases.reader import CASES_DIR
from pipelines.cli import main
from tests.hostile.corpus import DELETE, corpus
from tests.support.tomlw import dumps

ENTRIES = corpus()
assert len(ENTRIES) >= 150  # the corpus size


def apply_edits(data: dict, edits: dict) -> dict:
    """Set (or DELETE) dotted keys; numeric parts index lists; missing tables are created."""
    for dotted, value in edits.items():
        *path, last = dotted.split(".")
        cur = data
        for p in path:
            cur = cur[int(p)] if isinstance(cur, list) else cur.setdefault(p, {})
        if isinstance(cur, list):
            cur[int(last)] = value
        elif value == DELETE:
            cur.pop(last, None)
        else:
            cur[last] = value
    return data


def base_data(base: str) -> dict:
    data = tomllib.loads((CASES_DIR / f"{base}.toml").read_text())
    if isinstance(data.get("base"), str):  # sweep files name their base relative to themselves
        data["base"] = str(CASES_DIR / data["base"])
    return data


def raw_bytes(kind: str, text: str) -> bytes | None:
    """The bytes of a raw entry (None: the entry is not a file's content)."""
    rng = random.Random(15)
    return {
        "random_bytes": bytes(rng.randrange(256) for _ in range(400)),
        "utf16": text.encode("utf-16"),
        "latin1_comment": b"# caf\xe9 au lait\n" + text.encode(),
        "nul_byte": b"# a NUL \x00 byte\n" + text.encode(),
        "not_toml": b"this is not toml = = =\n",
        "huge": text.encode() + b"\n" + (b"# padding" * 40 + b"\n") * 3000,
        "truncated_table": text.encode() + b"\n[gears.sun\n",
        "bom_and_unknown_key": b"\xef\xbb\xbfzz = 1\n" + text.encode(),
    }.get(kind)


def write_inputs(tmp_path, command, base, edits, raw):
    """The case file(s) of an entry; returns the positional arguments."""
    case = tmp_path / "case.toml"
    text = dumps(apply_edits(base_data(base), edits)) + "\n"
    if raw == "directory":
        case.mkdir()
    elif raw == "missing":
        pass
    elif raw is not None:
        case.write_bytes(raw_bytes(raw, text))
    else:
        case.write_text(text)
    pos = [str(case)]
    if command == "compare":  # the second design is the valid shipped case
        second = tmp_path / "second.toml"
        second.write_text(dumps(base_data(base)) + "\n")
        pos.append(str(second))
    return pos


def check_refused(capsys, tmp_path, argv, expect: str, max_s: float = 3.0) -> str:
    """Run main(argv) and check the error contract; returns the error line."""
    before = {p.name: (p.read_bytes() if p.is_file() else None) for p in tmp_path.iterdir()}
    full = sorted(p.name for p in (tmp_path / "full").iterdir()) if (tmp_path / "full").is_dir() else None
    t0 = time.perf_counter()
    rc = main(argv)
    elapsed = time.perf_counter() - t0
    cap = capsys.readouterr()
    lines = cap.err.splitlines()
    assert rc == 2, cap.err
    assert "Traceback" not in cap.err and cap.out == ""
    errors = [ln for ln in lines if ": error: " in ln]
    assert len(errors) == 1 and errors == lines[-1:], cap.err  # progress lines may precede it, nothing after
    assert expect in errors[0], errors[0]
    after = {p.name: (p.read_bytes() if p.is_file() else None) for p in tmp_path.iterdir()}
    assert after == before  # no output folder, no staging or probe folder, files untouched
    if full is not None:
        assert sorted(p.name for p in (tmp_path / "full").iterdir()) == full
    assert elapsed < max_s, f"{elapsed:.2f} s: the check came after heavy work"
    return errors[0]


@pytest.mark.parametrize("entry", ENTRIES, ids=[e[0] for e in ENTRIES])
def test_hostile_input_is_refused_cleanly(entry, tmp_path, capsys):
    ident, command, base, edits, args, raw, expect = entry
    work = tmp_path / "w"
    work.mkdir()
    (work / "afile").write_text("x")
    (work / "full").mkdir()
    (work / "full" / "keep.txt").write_text("kept")
    pos = write_inputs(work, command, base, edits, raw)
    subst = {"{out}": str(work / "out"), "{file}": str(work / "afile"), "{full}": str(work / "full")}
    extra = [subst.get(a, a.replace("{file}", str(work / "afile"))) for a in args]
    if "--out" not in extra:
        extra = ["--out", str(work / "out")] + extra
    check_refused(capsys, work, [command, *pos, *extra], expect)
