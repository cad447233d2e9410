"""Worker processes that end with the process that started them.

A worker of a process pool (:mod:`certkit.engine.scheduler`, :mod:`certkit.design.parallel`) calls
:func:`die_with_parent`
first: on Linux the kernel sends it SIGKILL when its parent ends, however it ends (``prctl(PR_SET_PDEATHSIG)``,
see prctl(2)); elsewhere a daemon thread checks the parent every second. Workers ignore SIGINT: Ctrl-C reaches the
whole foreground process group, and the coordinator alone answers it (it stops the pool with :func:`stop_pool` and
exits 130), so no worker prints a traceback.
"""

from __future__ import annotations

import ctypes
import os
import signal
import sys
import threading
import time
from concurrent.futures import ProcessPoolExecutor

from certkit.user_cache import THREAD_SETTINGS  # stdlib only: no numpy loaded before the settings

_PR_SET_PDEATHSIG = 1  # <linux/prctl.h>


def die_with_parent(parent_pid: int) -> None:
    """Make this process end when ``parent_pid`` (the process that started it) ends."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    armed = False
    if sys.platform.startswith("linux"):
        try:
            libc = ctypes.CDLL(None, use_errno=True)
            armed = libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0) == 0
        except (OSError, AttributeError):
            armed = False
    if os.getppid() != parent_pid:  # the parent ended before the signal was armed
        os._exit(1)
    if not armed:
        threading.Thread(target=_watch, args=(parent_pid,), daemon=True, name="certkit-parent-watch").start()


def _watch(parent_pid: int) -> None:
    while os.getppid() == parent_pid:
        time.sleep(1.0)
    os._exit(1)


def stop_pool(pool: ProcessPoolExecutor) -> None:
    """End a :class:`concurrent.futures.ProcessPoolExecutor`'s workers now (interrupt, error): pending work is
    cancelled and running workers are terminated rather than awaited. ``_processes`` is the executor's own table of
    its workers (CPython 3.8–3.13); without it the pool is only shut down."""
    processes = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        if process.is_alive():
            process.terminate()
    for process in processes:
        process.join(timeout=5)


def one_blas_thread() -> None:
    """One BLAS/OpenMP thread per process, set before numpy loads (a user's own setting is kept): threaded BLAS in
    several processes oversubscribes the cores, and its summation order (the last digits of a result) would depend on
    the number of threads."""
    for var in THREAD_SETTINGS:
        os.environ.setdefault(var, "1")
