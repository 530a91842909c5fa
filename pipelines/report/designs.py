"""Two designs run side by side: each design's TCA, mesh, solve and pictures in its own process (``gearfe compare``).

The two designs of a comparison share no computation: their gears, TCAs (the new design's axial regulation),
meshes and solves differ. Only the colour ranges of their pictures are common (one von Mises range for both,
Fig. 1.9), and they are known once both are solved. So the work is split in two phases with one exchange:

    phase 1 (each design, in parallel):   TCA, mesh, contact solve, plots  -> its colour limits
    exchange:                             the parent takes the maxima of both designs' limits
    phase 2 (each design, in parallel):   pictures with the common ranges, reports -> its summary

The second design runs in a forked child process (the parent's modules, cases and memory are inherited;
only the limits and the JSON-ready summary cross the pipe). Much of each design's time is single-threaded
Python (the TCA, the regulation, the mesher, matplotlib and the off-screen renders), so on a 2-core machine
the two designs overlap instead of queueing; each process limits its BLAS/MKL (PARDISO) threads to
``threads`` so that the two solves do not oversubscribe the cores. Both designs' models are in memory at
once: ``jobs = 1`` (``gearfe compare --jobs 1``) runs them one after the other in this process.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import pickle
import traceback
from dataclasses import dataclass
from typing import Callable

__all__ = ["DesignSteps", "run_designs"]

try:
    from threadpoolctl import threadpool_limits
except ImportError:  # pragma: no cover - a declared dependency
    threadpool_limits = None


@dataclass(frozen=True)
class DesignSteps:
    """The two phases of one design, as callables of its label.

    ``solve(label)`` -> run (phase 1); ``limits(run)`` -> (zone von Mises limit, picture top) [MPa];
    ``finish(label, run, vm, top)`` -> the JSON-ready summary (phase 2, pictures on the common ranges).
    """

    solve: Callable
    limits: Callable
    finish: Callable


def _threads(n: int | None):
    if n is None or threadpool_limits is None:
        return contextlib.nullcontext()
    return threadpool_limits(limits=n)


def _serial(labels, steps: DesignSteps) -> dict:
    runs = {k: steps.solve(k) for k in labels}
    lims = [steps.limits(runs[k]) for k in labels]
    vm, top = max(x[0] for x in lims), max(x[1] for x in lims)
    return {k: steps.finish(k, runs.pop(k), vm, top) for k in labels}


def _child(conn, label: str, steps: DesignSteps, threads: int | None) -> None:
    """The second design in the forked process: phase 1, send limits, receive the ranges, phase 2, send the summary."""
    try:
        with _threads(threads):
            run = steps.solve(label)
            conn.send(("limits", steps.limits(run)))
            msg = conn.recv()
            if msg[0] != "ranges":  # the parent failed: stop quietly
                return
            conn.send(("summary", steps.finish(label, run, *msg[1])))
    except BaseException as exc:  # noqa: BLE001 - every failure goes back to the parent, which raises it
        try:  # the class by reference, its args and attributes: rebuilt without calling its __init__
            payload = pickle.dumps((type(exc), exc.args, vars(exc)))
            _rebuild(payload)
        except Exception:  # an exception that cannot be rebuilt is sent as text
            payload = None
        conn.send(("error", payload, f"{type(exc).__name__}: {exc}", traceback.format_exc()))
    finally:
        conn.close()


def _rebuild(payload: bytes) -> BaseException:
    """An exception from (class, args, attributes): the user errors' own __init__ takes other arguments than args."""
    cls, args, attrs = pickle.loads(payload)
    exc = cls.__new__(cls)
    exc.args = args
    exc.__dict__.update(attrs)
    return exc


def _receive(conn, proc, expect: str):
    """The child's next message of kind ``expect``; its exception is raised here."""
    try:
        msg = conn.recv()
    except EOFError:
        raise RuntimeError(f"the second design's process ended without a result (exit code {proc.exitcode})") from None
    if msg[0] == "error":
        if msg[1] is not None:
            raise _rebuild(msg[1])
        raise RuntimeError(f"the second design failed: {msg[2]}\n{msg[3]}")
    if msg[0] != expect:
        raise RuntimeError(f"the second design's process sent {msg[0]!r} where {expect!r} was expected")
    return msg[1]


def run_designs(labels: tuple, steps: DesignSteps, jobs: int = 2, threads: int | None = 1) -> dict:
    """Summaries of the designs ``labels`` (module docstring): the second in a forked process when ``jobs`` >= 2
    and the platform forks, else one after the other. ``threads``: BLAS/MKL threads of each process while both run."""
    labels = tuple(labels)
    if jobs < 2 or len(labels) != 2 or "fork" not in multiprocessing.get_all_start_methods():
        return _serial(labels, steps)
    first, second = labels
    ctx = multiprocessing.get_context("fork")
    parent, child = ctx.Pipe()
    proc = ctx.Process(target=_child, args=(child, second, steps, threads), name=f"gearfe-{second}", daemon=True)
    proc.start()
    child.close()
    ok = False
    try:
        with _threads(threads):
            run = steps.solve(first)
            mine = steps.limits(run)
        theirs = _receive(parent, proc, "limits")
        vm, top = max(mine[0], theirs[0]), max(mine[1], theirs[1])
        parent.send(("ranges", (vm, top)))
        with _threads(threads):
            s_first = steps.finish(first, run, vm, top)
        del run
        s_second = _receive(parent, proc, "summary")
        ok = True
    finally:
        if not ok and proc.is_alive():
            with contextlib.suppress(Exception):
                parent.send(("stop",))
            proc.join(5)
            if proc.is_alive():
                proc.terminate()
        proc.join()
        parent.close()
    return {first: s_first, second: s_second}
