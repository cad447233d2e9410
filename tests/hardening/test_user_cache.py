"""The user cache (pint's parsed unit definitions, the rule index) is only a speed-up: a truncated or half-written
file, as a killed process or two processes starting together leave it, costs time, never a run (the CI failure of
stop 22: `certkit explain` exited 70 on ``EOFError: Ran out of input`` from pint's cache)."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys

from jinja2.bccache import bc_magic

PROBE = "from certkit.units import to_si; print(to_si('1000 ft', 'length'))"


def _run(cache):
    return subprocess.Popen(
        [sys.executable, "-c", PROBE],
        env={**os.environ, "XDG_CACHE_HOME": str(cache)},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def _ok(proc):
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 0, err
    assert abs(float(out) - 304.8) < 1e-9  # 1000 ft = 304.8 m exactly (international foot)


def test_truncated_unit_cache_is_rebuilt(tmp_path):
    _ok(_run(tmp_path))
    pickles = sorted((tmp_path / "certkit" / "pint").glob("*.pickle"))
    assert pickles, "pint's definitions are cached in certkit's cache folder"
    for p in pickles:
        with open(p, "r+b") as f:
            f.truncate(20)  # as a process killed mid-write leaves it
    _ok(_run(tmp_path))
    for p in pickles:  # rebuilt, not left truncated
        with open(p, "rb") as f:
            pickle.load(f)


def test_processes_starting_together_on_an_empty_cache(tmp_path):
    procs = [_run(tmp_path) for _ in range(6)]
    for proc in procs:
        _ok(proc)


TEMPLATES = (
    "from certkit.report.html import _environment; "
    "print(_environment(set()).get_template('report.html').name, _environment(set()).get_template('report.html').name)"
)


def _templates(cache):
    proc = subprocess.run(
        [sys.executable, "-c", TEMPLATES],
        env={**os.environ, "XDG_CACHE_HOME": str(cache)},
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split() == ["report.html", "report.html"]


def test_compiled_templates_are_cached_and_a_damaged_cache_is_compiled_afresh(tmp_path):
    _templates(tmp_path)
    compiled = sorted((tmp_path / "certkit" / "templates").glob("*.cache"))
    assert compiled, "the report's compiled templates are kept in certkit's cache folder"
    for p in compiled:
        with open(p, "r+b") as f:
            f.truncate(len(bc_magic) + 2)  # within the checksum's pickle: Jinja itself would raise UnpicklingError
    _templates(tmp_path)
    (tmp_path / "unwritable").write_text("a file where the cache folder would be")
    _templates(tmp_path / "unwritable")  # no folder can be made: the templates are compiled each time


def test_the_suite_writes_into_a_cache_folder_of_its_own():
    """The tests' lattice solutions and indexes go to the session's folder (tests/conftest.py), not the user's: a
    lattice solved in a test process (BLAS threads of its own) and loaded by a later `certkit check` would change the
    last bits of that check's results.json."""
    from pathlib import Path

    from certkit.user_cache import cache_folder

    user = Path(os.path.expanduser("~")) / ".cache" / "certkit"
    assert cache_folder() != user and "certkit-test-cache-" in str(cache_folder())
