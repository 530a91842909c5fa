"""SIGINT and SIGTERM that stop a run even where a library swallows the exception they raise.

The handlers record the signal and raise :class:`KeyboardInterrupt` (SIGINT) or :class:`Terminated`
(SIGTERM) in the main thread. Some third-party code runs imports or callbacks under a bare
``except:``, which would swallow that exception and let the run finish as if nothing had happened
(seen once: a fresh clone, whose first imports compile the modules, ran a Ctrl-C'd ``gearfe stress``
to the end). Every progress line of the CLI therefore calls :func:`check_interrupted`, which raises
again while a signal is pending: the run stops at its next stage at the latest.
"""

from __future__ import annotations

import signal

__all__ = ["Terminated", "check_interrupted", "install", "restore"]


class Terminated(BaseException):
    """Raised in the main thread on SIGTERM, so that staged output is cleaned up like on Ctrl-C."""


_pending: list[int] = []


def _raise(signum: int):
    if signum == signal.SIGTERM:
        raise Terminated()
    raise KeyboardInterrupt()


def _on_signal(signum, frame):
    _pending.append(signum)
    _raise(signum)


def check_interrupted() -> None:
    """Raise the exception of a pending SIGINT / SIGTERM (a no-op when none arrived)."""
    if _pending:
        _raise(_pending[0])


def install() -> dict:
    """Install the handlers (main thread only; elsewhere nothing changes); the previous ones."""
    _pending.clear()
    old = {}
    for sig in (signal.SIGINT, signal.SIGTERM):
        try:
            old[sig] = signal.signal(sig, _on_signal)
        except ValueError:  # not the main thread (e.g. called from a worker): default handling
            break
    return old


def restore(old: dict) -> None:
    """Put back the handlers that :func:`install` replaced and forget pending signals."""
    for sig, h in old.items():
        signal.signal(sig, h)
    _pending.clear()
