"""Ctrl-C in the command-line program: noticed once, answered surely.

:func:`install` replaces Python's SIGINT handler with one that also *records* the interrupt before raising
KeyboardInterrupt as usual. A KeyboardInterrupt can be lost where Python cannot raise it (a finaliser, a callback
whose exceptions are ignored); the record is not: :func:`raise_if_requested` raises it again where it matters — before
outputs replace the previous ones — so an interrupted run never writes. :func:`leave` ends the process at once with
the given code after flushing the standard streams: the interpreter's shutdown after an interrupt (the process pool's
exit hook writing to a pipe its manager already closed; CPython then ending itself with SIGINT) printed tracebacks or
turned exit code 130 into death by signal, about one run in ten.
"""

from __future__ import annotations

import os
import signal
import sys
from types import FrameType
from typing import NoReturn

_state = {"requested": False}


def on_interrupt(signum: int, frame: FrameType | None) -> NoReturn:
    """The handler: record the interrupt, then raise KeyboardInterrupt as Python's own handler does."""
    _state["requested"] = True
    raise KeyboardInterrupt


def install() -> None:
    """Record every SIGINT of this process (the main thread's handler; call it from the main thread)."""
    signal.signal(signal.SIGINT, on_interrupt)


def requested() -> bool:
    return _state["requested"]


def raise_if_requested() -> None:
    """Raise KeyboardInterrupt if an interrupt came, even one that was swallowed on its way up."""
    if _state["requested"]:
        raise KeyboardInterrupt


def leave(code: int) -> None:
    """End the process now with ``code``: flush stdout and stderr, skip the interpreter's shutdown."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass
    os._exit(code)
