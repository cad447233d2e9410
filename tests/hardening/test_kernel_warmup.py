"""Compiling certkit's kernels ahead at the first run (certkit/models/kernel_warmup.py): the list of kernels is what
the rules compile, every entry can be compiled from its text, and the groups keep modules whole."""

import os
import subprocess
import sys

import pytest

from certkit.models.kernel_warmup import (
    COMPILED_ELSEWHERE,
    EQUATIONS_OF_MOTION,
    SIGNATURES_FILE,
    argument_types,
    groups,
    listed_signatures,
)

from ..conftest import ROOT


def test_the_list_is_what_a_check_and_a_design_evaluation_compile(tmp_path):
    """Fails when a kernel gains, loses or changes an argument type (the first run would compile it in every process
    again); the message holds the new list. The script runs from another folder, so that it imports the certkit the
    tests import (an installed copy's kernels are already compiled by the other tests)."""
    done = subprocess.run(
        [sys.executable, str(ROOT / "tests" / "hardening" / "kernel_usage.py")],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        env={**os.environ, "OMP_NUM_THREADS": "1"},
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout == SIGNATURES_FILE.read_text(encoding="utf-8"), (
        "certkit/models/kernel_signatures.txt is stale; rewrite it with "
        "`python tests/hardening/kernel_usage.py > certkit/models/kernel_signatures.txt`:\n" + done.stdout
    )


def test_every_listed_signature_reads_as_numba_types():
    from numba.core import types

    entries = listed_signatures()
    assert len(entries) >= 20
    for module, function, text in entries:
        parsed = argument_types(text)
        assert parsed and all(isinstance(t, types.Type) for t in parsed), (module, function, text)
        assert str(parsed) == text  # read back as written


def test_groups_keep_each_module_whole_and_the_equations_of_motion_alone():
    eom, runs = EQUATIONS_OF_MOTION
    modules = [(eom, 3), ("a", 4), (runs, 1), ("b", 2), ("c", 1)]
    entries = [(m, f"f{k}", "()") for m, n in modules for k in range(n)]
    parts = groups(entries, 3)
    assert sorted(e for g in parts for e in g) == sorted(entries)  # nothing lost, nothing twice
    assert [e[0] for e in parts[0]] == [eom] * 3 + [runs]
    assert all(len({e[0] for e in g} & {"a", "b", "c"}) >= 1 for g in parts[1:])
    for module in ("a", "b", "c"):
        assert sum(any(e[0] == module for e in g) for g in parts) == 1
    assert groups(entries, 1) == [entries]
    assert len(groups(entries, 8)) == 4  # no empty group
    # the kernels compiled elsewhere go last into the last group, behind that group's own modules, whichever module
    # they belong to (the open-loop run of the equations' module, the trims' residual of its own)
    assert {m for m, _ in COMPILED_ELSEWHERE} - set(EQUATIONS_OF_MOTION)
    late = [(module, function, "()") for module, function in COMPILED_ELSEWHERE]
    own = [(module, "g", "()") for module, _ in COMPILED_ELSEWHERE if module not in EQUATIONS_OF_MOTION]
    parts = groups(entries + own + late, 2)
    assert len(parts) == 2 and not set(late) & set(parts[0]) and parts[-1][-len(late) :] == late
    assert all(e in parts[-1][: -len(late)] for e in own)  # their modules' other kernels stay in their group
    assert groups([e for e in entries if e[0] in EQUATIONS_OF_MOTION] + late, 2)[-1] == late


@pytest.mark.parametrize("processes", [2, 1])
def test_the_kernels_are_compiled_into_the_cache_by_other_processes(tmp_path, processes):
    """Two small kernels of two modules compiled ahead land in an empty cache, where a new process finds them (numba's
    index file per kernel); with one job too another process compiles them, and the calling process has compiled none
    itself: it runs them from the cache (the module's docstring: a process that compiled a kernel runs other last bits
    than the cached one)."""
    script = (
        "import importlib\n"
        "from certkit.models.kernel_warmup import compile_kernels, listed_signatures\n"
        "entries = [e for e in listed_signatures() if e[1] in ('_first_out_of_range', '_worst')]\n"
        "assert len({e[0] for e in entries}) == 2, entries\n"
        f"print(compile_kernels({processes}, entries) > 0)\n"
        "print(sum(len(getattr(importlib.import_module(m), f).signatures) for m, f, _ in entries))\n"
    )
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env, cwd=ROOT)
    assert done.stdout.split() == ["True", "0"], done.stderr[-3000:]
    indexes = sorted(p.name.split("-")[0] for p in tmp_path.rglob("*.nbi"))
    assert indexes == ["atmosphere._first_out_of_range", "capability._worst"]


def test_a_cache_is_warm_only_once_the_whole_list_is_compiled(tmp_path):
    """An interrupted first run leaves some kernels in the cache and not the others: the next run still compiles ahead
    (else it would compile the missing ones where they run, with that process's own last bits). The cache counts as
    warm once a compilation of the whole list has finished, and only for that list: a list with more kernels (or
    changed sources, in the stamp too) makes it cold again. Here the whole list is two small kernels."""
    script = (
        "from certkit.models import kernel_warmup as kw\n"
        "full = kw.listed_signatures()\n"
        "small = [e for e in full if e[1] in ('_first_out_of_range', '_worst')]\n"
        "print(kw.kernels_cached())\n"
        "kw.compile_kernels(1, small[:1])\n"  # the first run stopped after one kernel
        "kw.listed_signatures = lambda: small\n"
        "print(kw.kernels_cached())\n"
        "kw.compile_kernels(1)\n"  # the whole (two-kernel) list
        "print(kw.kernels_cached())\n"
        "kw.listed_signatures = lambda: full\n"
        "print(kw.kernels_cached())\n"
    )
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env, cwd=ROOT)
    assert done.stdout.split() == ["False", "False", "True", "False"], done.stderr[-3000:]
    assert len(list(tmp_path.rglob("*.nbi"))) == 2
