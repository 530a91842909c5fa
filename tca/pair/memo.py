"""Results computed once per process: a small memo keyed by the *values* of frozen inputs.

A pair's TCA depends only on the pair (gears, modifications, misalignment, mounts) and the options.
Several stages of one run ask for the same TCA: ``gearfe run`` (the TCA stage, then the stress model's
position), ``gearfe compare`` of designs that share a mesh, and a sweep's points over torques and
positions of one geometry in a worker process. :class:`Memo` returns the earlier result for inputs of
equal value.

Key: :func:`fingerprint`, a hashable tuple of the inputs' values: a dataclass by its type and its
fields that take part in equality (``compare=True``; the lazily filled ``_cache`` fields of gears do
not), arrays by dtype, shape and bytes, numbers with their type (``True`` is not ``1``; ``nan`` never
matches, so it is recomputed). An input with any other kind of value (a callable, an arbitrary
object) has no fingerprint and is simply computed.

A stored result is shared by every caller: its arrays are made read-only (``ndarray.flags.writeable``
False, through dataclass fields, tuples, lists and dicts), so a caller that would modify it in place
fails at once instead of changing the result seen by the next caller.

Shared between processes (:meth:`Memo.share`): results are also kept as files in a folder, one pickle per key
named by the SHA-256 of the pickled key, written under a temporary name and renamed into place (a reader never
sees half a file), so processes that share the folder (the test suite's two workers and the processes they fork)
compute a result once. A key whose pickle does not read back equal (a ``nan`` in the inputs) is not shared. The
folder belongs to whoever shares it: results are not checked against the code that wrote them, so a folder must
not outlive the code (the test suite makes one per session and removes it).
"""

from __future__ import annotations

import dataclasses
import enum
import hashlib
import os
import pickle
from collections import OrderedDict
from pathlib import Path
from typing import Callable, Hashable

import numpy as np

__all__ = ["Unkeyable", "fingerprint", "freeze_arrays", "Memo"]


class Unkeyable(TypeError):
    """An input holds a value that :func:`fingerprint` does not key (it is computed, not memoised)."""


def fingerprint(obj) -> Hashable:
    """A hashable tuple equal for inputs of equal value (see the module docstring)."""
    if obj is None or isinstance(obj, (str, bytes)):
        return obj
    if isinstance(obj, enum.Enum):
        return (type(obj).__qualname__, obj.value)
    if isinstance(obj, (bool, int, float, complex, np.generic)):
        return (type(obj).__name__, obj.item() if isinstance(obj, np.generic) else obj)
    if isinstance(obj, np.ndarray):
        if obj.dtype == object:
            raise Unkeyable("an array of Python objects")
        return ("ndarray", obj.dtype.str, obj.shape, np.ascontiguousarray(obj).tobytes())
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return (type(obj).__module__, type(obj).__qualname__,
                tuple((f.name, fingerprint(getattr(obj, f.name))) for f in dataclasses.fields(obj) if f.compare))
    if isinstance(obj, (tuple, list)):
        return (type(obj).__name__, tuple(fingerprint(v) for v in obj))
    if isinstance(obj, dict):
        return ("dict", tuple(sorted((repr(k), fingerprint(v)) for k, v in obj.items())))
    raise Unkeyable(f"a value of type {type(obj).__qualname__}")


def freeze_arrays(obj, _seen=None) -> None:
    """Make every array reachable through dataclass fields, tuples, lists and dicts read-only."""
    seen = set() if _seen is None else _seen
    if id(obj) in seen:
        return
    seen.add(id(obj))
    if isinstance(obj, np.ndarray):
        obj.flags.writeable = False
    elif dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        for f in dataclasses.fields(obj):
            freeze_arrays(getattr(obj, f.name), seen)
    elif isinstance(obj, (tuple, list)):
        for v in obj:
            freeze_arrays(v, seen)
    elif isinstance(obj, dict):
        for v in obj.values():
            freeze_arrays(v, seen)


class Memo:
    """The last ``size`` results of ``compute(*args)``, looked up by the fingerprint of ``args``."""

    def __init__(self, compute: Callable, size: int = 8):
        self.compute, self.size = compute, size
        self._store: OrderedDict = OrderedDict()
        self.hits = self.misses = 0
        self.folder: Path | None = None

    def share(self, folder: Path | None) -> None:
        """Keep results also as files in ``folder``, read by every process that shares it (module docstring);
        None: this process only."""
        self.folder = None if folder is None else Path(folder)

    def _file(self, key) -> Path | None:
        """The file of ``key`` in the shared folder, None when not shared (no folder, or a key that does not
        read back equal)."""
        if self.folder is None:
            return None
        blob = pickle.dumps(key, protocol=pickle.HIGHEST_PROTOCOL)
        if pickle.loads(blob) != key:
            return None
        return self.folder / f"{hashlib.sha256(blob).hexdigest()}.pkl"

    def __call__(self, *args):
        try:
            key = fingerprint(args)
        except Unkeyable:
            self.misses += 1
            return self.compute(*args)
        if key in self._store:
            self._store.move_to_end(key)
            self.hits += 1
            return self._store[key]
        path = self._file(key)
        if path is not None and path.is_file():
            self.hits += 1
            result = pickle.loads(path.read_bytes())
        else:
            self.misses += 1
            result = self.compute(*args)
            if path is not None:
                tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
                tmp.write_bytes(pickle.dumps(result, protocol=pickle.HIGHEST_PROTOCOL))
                os.replace(tmp, path)
        freeze_arrays(result)
        self._store[key] = result
        while len(self._store) > self.size:
            self._store.popitem(last=False)
        return result

    def clear(self) -> None:
        self._store.clear()
