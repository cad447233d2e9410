"""Compiling certkit's numba kernels before their first use, several modules at once in parallel processes.

numba compiles a kernel the first time it is called with a new combination of argument types, in the process that
calls it, and caches the machine code on disk. At the first run after an install every process of a
``certkit check --jobs N`` (or of a study) would compile the kernels its rules call — the same kernels in each
process, one after the other within a process. Here the kernels are compiled once, ahead, with the argument types
the rules call them with (:data:`SIGNATURES_FILE`, one line per compiled kernel: module, function, argument types),
one group of modules per process (:func:`groups`: the equations of motion, the largest, alone); the rules then load
them from the cache.

Even for one job the kernels are compiled by another process: numba runs the machine code it has just compiled in the
process that compiled it and writes an object file to its cache that later processes load, and for certkit's
fast-math kernels the two do not compute the same last bits (the open-loop run replayed on 30 recorded calls of a
design: other states when compiled in the replaying process than when loaded from the cache that very compilation
wrote; the seed study's 20-case records then differ in 3,443 of 50,393 values, 2026-12-07). Every result thus comes
from the cached code, whichever run compiled it: a first check after an install gives the bits of the next ones.

The list is a record of what certkit's rules compile; a test compares it with the kernels a check and a design
evaluation compile (``tests/hardening/test_kernel_warmup.py``, which prints the new list when it differs). A kernel
called with types the list lacks is still compiled where it is called, and that run computes with its own machine code
(the last bits above): the test keeps the list complete.
"""

from __future__ import annotations

import hashlib
import importlib
import multiprocessing
import sys
import time
from collections.abc import Callable, Iterable
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

#: the kernels to compile ahead: ``module function (argument types)`` per line, as numba writes the types
SIGNATURES_FILE = Path(__file__).with_name("kernel_signatures.txt")
#: the modules compiled together in a process of their own: the equations of motion (they inline most of the others'
#: work: about half of the compile time) and the compiled closed-loop runs, which call them (compiled elsewhere they
#: would compile the equations once more: 15 s against 5 s after them, 2026-12-06)
EQUATIONS_OF_MOTION = ("certkit.models.dynamics.kernel", "certkit.models.dynamics.pilot_kernel")
#: kernels compiled last in another process: they call the equations of motion, which that process then loads from the
#: cache the first has written by then, and nothing in the first needs them (the open-loop run: about 5 s of the first
#: process's 18 s moved behind the other's 7 s; the trims' residual, in the order of its own module, made the first run
#: compile 2.7 s longer, 2026-12-07)
COMPILED_ELSEWHERE = (
    ("certkit.models.dynamics.kernel", "integrate_open_loop"),
    ("certkit.models.dynamics.trim", "_residual_rows"),
)

#: the file, beside numba's cache of the equations of motion, that a finished :func:`compile_kernels` of the whole list
#: writes (:func:`completion_stamp`): a first run interrupted while compiling leaves the cache without it
COMPLETE_FILE = "certkit-kernels.complete"

Entry = tuple[str, str, str]  # module, function, argument types (numba's text)


def listed_signatures(path: Path = SIGNATURES_FILE) -> list[Entry]:
    """The entries of the signatures file (blank lines and ``#`` comments skipped)."""
    out = []
    for line in path.read_text(encoding="utf-8").splitlines():
        line = line.strip()
        if line and not line.startswith("#"):
            module, function, types = line.split(" ", 2)
            out.append((module, function, types))
    return out


def used_signatures(modules: Iterable[str] | None = None) -> list[Entry]:
    """The kernels this process has compiled or loaded, with their argument types, sorted (certkit's modules only)."""
    from numba.core.registry import (  # deferred: numba only where kernels compile (study commands import this)
        CPUDispatcher,
    )

    names = sorted(sys.modules) if modules is None else sorted(modules)
    out = []
    for name in names:
        module = sys.modules.get(name)
        if module is None or not name.startswith("certkit"):
            continue
        for function, value in sorted(vars(module).items()):
            if isinstance(value, CPUDispatcher) and value.__module__ == name:
                out += [(name, function, str(sig)) for sig in value.signatures]
    return sorted(set(out))


def argument_types(text: str) -> tuple[Any, ...]:
    """numba's argument types from their text (``(Array(float64, 2, 'C', False, aligned=True), int64)``)."""
    from numba.core import types  # deferred: numba only where kernels compile (study commands import this)

    names = {
        "Array": types.Array,
        "float64": types.float64,
        "int64": types.int64,
        "bool": types.boolean,
        "False": False,
        "True": True,
    }
    value = eval(text, {"__builtins__": {}}, names)  # noqa: S307 - the package's own file, names restricted
    return value if isinstance(value, tuple) else (value,)


def compile_group(entries: list[Entry]) -> float:
    """Compile (or load from numba's cache) each entry's kernel for its argument types; the seconds taken."""
    start = time.perf_counter()
    for module, function, types in entries:
        dispatcher = getattr(importlib.import_module(module), function)
        dispatcher.compile(argument_types(types))
    return time.perf_counter() - start


def groups(entries: list[Entry], processes: int) -> list[list[Entry]]:
    """The entries in at most ``processes`` groups of whole modules: those of :data:`EQUATIONS_OF_MOTION` alone
    together, the others dealt in turn to the group with the fewest kernels (a kernel called by another module's
    compiles with it either way), then those of :data:`COMPILED_ELSEWHERE` (of any module) at the end of the last
    group."""
    by_module: dict[str, list[Entry]] = {}
    for e in entries:
        by_module.setdefault(e[0], []).append(e)
    if processes < 2 or len(by_module) < 2:
        return [list(entries)] if entries else []
    later = [e for e in entries if e[:2] in COMPILED_ELSEWHERE]
    by_module = {m: [e for e in es if e not in later] for m, es in by_module.items()}
    by_module = {m: es for m, es in by_module.items() if es}
    first = [e for module in EQUATIONS_OF_MOTION for e in by_module.pop(module, [])]
    rest: list[list[Entry]] = [[] for _ in range(processes - 1 if first else processes)]
    for module in sorted(by_module, key=lambda m: -len(by_module[m])):
        min(rest, key=len).extend(by_module[module])
    parts = [g for g in ([first] if first else []) + rest if g]
    if later:
        if len(parts) < 2:
            parts.append([])
        parts[-1].extend(later)
    return parts


def compile_kernels(processes: int, entries: list[Entry] | None = None, context: str = "fork") -> float:
    """Compile the listed kernels (:func:`listed_signatures`) in up to ``processes`` processes (started by the
    multiprocessing ``context``; spawn for a caller with threads), each group of modules in its own, into numba's disk
    cache; the wall seconds taken. One process too (``--jobs 1``): another process compiles them, so that the process
    that uses them runs the machine code numba loads from the cache — the kernels compiled where they run give other
    last bits than the same kernels loaded from the cache (the module's docstring)."""
    whole = entries is None
    entries = listed_signatures() if entries is None else entries
    if not entries:
        return 0.0
    from certkit.models import compiled  # deferred: numba only where kernels compile (study commands)

    start = time.perf_counter()
    # the stale-kernel refresh once, here, before the workers write into the cache: a worker that ran it first would
    # find no digest beside a fresh cache and remove what the other had just compiled
    compiled.refresh_stale_kernels()
    parts = groups(entries, processes)
    with ProcessPoolExecutor(len(parts), mp_context=multiprocessing.get_context(context)) as pool:
        list(pool.map(compile_group, parts))
    path = completion_file() if whole else None
    if path is not None:  # every listed kernel is in the cache now (:func:`kernels_cached`)
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(completion_stamp(entries, path), encoding="utf-8")
        except OSError:  # a cache numba cannot write either: it compiles in memory
            pass
    return time.perf_counter() - start


def completion_stamp(entries: list[Entry], path: Path) -> str:
    """What :data:`COMPLETE_FILE` ``path`` holds once ``entries`` are compiled: a digest of the kernel sources' digest
    beside it (:func:`certkit.models.compiled.refresh_stale_kernels` keeps it current) and of the entries (a changed
    source or list makes it another)."""
    from certkit.models import compiled  # deferred: numba only where kernels compile (study commands)

    sources = (path.parent / compiled.DIGEST_FILE).read_text(encoding="utf-8")
    listed = "\n".join(" ".join(e) for e in entries)
    return hashlib.sha256(f"{sources}\n{listed}".encode()).hexdigest()


def completion_file() -> Path | None:
    """:data:`COMPLETE_FILE` in numba's cache directory of the equations of motion (None: numba caches nothing)."""
    from certkit.models import compiled  # deferred: numba only where kernels compile (study commands)

    package = Path(compiled.__file__).resolve().parents[1]
    for directory, stems in compiled.kernel_cache_dirs(package).items():
        if "kernel" in stems:
            return directory / COMPLETE_FILE
    return None


def kernels_cached() -> bool:
    """Has a :func:`compile_kernels` of the whole list finished into numba's cache since the kernel sources last
    changed (False at the first run after an install, and after a first run that was interrupted while compiling:
    the kernels are then compiled ahead, and the command says so before it goes quiet for a while)?"""
    path = completion_file()
    if path is None:
        return True  # numba cannot cache here: each process compiles for itself, nothing ahead would help
    try:
        return path.read_text(encoding="utf-8") == completion_stamp(listed_signatures(), path)
    except OSError:
        return False


def compile_if_cold(processes: int, context: str = "fork", starting: Callable[[], None] | None = None) -> float | None:
    """At the first run after an install (numba's cache cold: :func:`kernels_cached`), call ``starting`` (e.g. to say
    so) and :func:`compile_kernels`; its seconds, or None when the kernels are cached."""
    if kernels_cached():
        return None
    if starting is not None:
        starting()
    return compile_kernels(processes, context=context)


__all__ = [
    "SIGNATURES_FILE",
    "COMPILED_ELSEWHERE",
    "EQUATIONS_OF_MOTION",
    "COMPLETE_FILE",
    "compile_if_cold",
    "completion_file",
    "completion_stamp",
    "kernels_cached",
    "argument_types",
    "compile_group",
    "compile_kernels",
    "groups",
    "listed_signatures",
    "used_signatures",
]
