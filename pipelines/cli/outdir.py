"""Result folders written all-or-nothing: files go to a temporary sibling, then are renamed in.

:func:`check_out` vets ``--out`` before any work: not empty, not an existing file, not under a
file, creatable and writable (probed by making and removing a temporary folder beside it), and,
when it exists and holds files, only with ``--force`` (then same-named files are replaced, others
kept) or, for resumable commands (``gearfe sweep``), when it holds that command's own marker file.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from pathlib import Path

from tca.errors import InputError

__all__ = ["staged_output", "atomic_write_text", "check_out"]


STAGE_NAME_MAX = 200  # characters of --out's name kept in the staging folder's name (.NAME.tmp- and a random suffix)


@contextlib.contextmanager
def staged_output(out: str | os.PathLike):
    """Yield a temporary folder; on success move its files into `out`, on error delete it.

    A command that fails (bad input, a solve that does not converge) therefore leaves no
    partial result files behind; files already in `out` from earlier runs are only replaced
    once the new run has finished.
    """
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{out.name[:STAGE_NAME_MAX]}.tmp-", dir=out.parent))
    try:
        yield tmp
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    out.mkdir(parents=True, exist_ok=True)
    for src in sorted(tmp.rglob("*")):
        dst = out / src.relative_to(tmp)
        if src.is_dir():
            dst.mkdir(parents=True, exist_ok=True)
        else:
            dst.parent.mkdir(parents=True, exist_ok=True)
            os.replace(src, dst)
    shutil.rmtree(tmp, ignore_errors=True)


def atomic_write_text(path: str | os.PathLike, text: str) -> None:
    """Write a text file under a temporary name and rename it into place."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    try:
        with os.fdopen(fd, "w") as fh:
            fh.write(text)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def check_out(out: str, force: bool = False, resume_marker: str | None = None) -> Path:
    """Validate an output folder before any work (module docstring); InputError naming ``--out``."""
    if not isinstance(out, str) or not out.strip():
        raise InputError("--out", out, "a folder name (not empty)")
    if "\x00" in out:
        raise InputError("--out", out, "a folder name without NUL characters")
    path = Path(out)
    try:
        if path.exists() or path.is_symlink():
            if not path.is_dir():
                raise InputError("--out", out, "a folder (it is an existing file)")
            if any(path.iterdir()) and not force and not (resume_marker and (path / resume_marker).is_file()):
                raise InputError("--out", out, "an empty or new folder, or --force to write into it",
                                 "it exists and is not empty")
            _probe(path, out)
            return path
        anc = path.absolute().parent
        while not anc.exists():
            anc = anc.parent
        if not anc.is_dir():
            raise InputError("--out", out, "a folder path", f"{anc} is a file")
        _check_names(path, anc, out)
        _probe(anc, out)
    except OSError as e:
        raise InputError("--out", out, "a writable folder", e.strerror or type(e).__name__) from None
    return path


def _check_names(path: Path, anc: Path, out: str) -> None:
    """Every folder still to be made fits the file system's name length (NAME_MAX) and the path length (PATH_MAX)."""
    try:
        name_max = os.pathconf(anc, "PC_NAME_MAX")
        path_max = os.pathconf(anc, "PC_PATH_MAX")
    except (OSError, ValueError):
        name_max, path_max = 255, 4096
    new = path.absolute().relative_to(anc).parts
    for part in new:
        if len(part.encode()) > name_max:
            raise InputError("--out", out, f"a folder whose names have at most {name_max} bytes (the file system's limit)",
                             f"{part[:20]}... has {len(part.encode())}")
    if len(str(path.absolute()).encode()) + 32 > path_max:
        raise InputError("--out", out, f"a path of at most {path_max - 32} bytes", "too long for the file system")


def _probe(folder: Path, out: str) -> None:
    """Make and remove a temporary folder in `folder`: read-only, immutable or virtual places fail here."""
    if not os.access(folder, os.W_OK | os.X_OK):
        raise InputError("--out", out, "a writable folder", f"no write permission in {folder}")
    try:
        tmp = tempfile.mkdtemp(prefix=".gearfe-probe-", dir=folder)
    except OSError as e:
        why = (os.strerror(e.errno) if e.errno else type(e).__name__) + f" in {folder}"
        raise InputError("--out", out, "a writable folder", why) from None
    os.rmdir(tmp)
