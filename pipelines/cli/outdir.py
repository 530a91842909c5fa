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


@contextlib.contextmanager
def staged_output(out: str | os.PathLike):
    """Yield a temporary folder; on success move its files into `out`, on error delete it.

    A command that fails (bad input, a solve that does not converge) therefore leaves no
    partial result files behind; files already in `out` from earlier runs are only replaced
    once the new run has finished.
    """
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{out.name}.tmp-", dir=out.parent))
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
        _probe(anc, out)
    except OSError as e:
        raise InputError("--out", out, "a writable folder", e.strerror or type(e).__name__) from None
    return path


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
