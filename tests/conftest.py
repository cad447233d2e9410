"""Shared fixtures: the bundled baseline, a CLI runner and (tests/browser.py) the headless browser."""

import importlib.util
import os
import shutil
import tempfile
from pathlib import Path

import pytest
from click.testing import CliRunner

from certkit.aircraft import load_aircraft
from certkit.cli.main import main
from certkit.engine.context import Context
from certkit.engine.worker_processes import one_blas_thread

#: the headless-browser fixture (``browser``) of the report tests
pytest_plugins = ["tests.browser"]

ROOT = Path(__file__).resolve().parents[1]
BASELINE = ROOT / "aircraft" / "lta.yaml"
SHARED_REFERENCE = ROOT.parent / "shared" / "reference"


def pytest_configure(config):
    """The suite's own certkit cache folder (``XDG_CACHE_HOME``, a temporary directory for the session, set by the
    controller before pytest-xdist starts its workers, which inherit it): the tests' lattice solutions — solved in test
    processes, whose BLAS may run several threads and sum in another order — never enter the user's folder, where a
    later ``certkit check`` would load them and give other last bits than its own solution. One BLAS thread per worker
    (as certkit's own worker processes have it, a user's setting kept): two workers each with a threaded BLAS on two
    cores spin against each other (a file of rule tests took 14.7 s instead of 6.8 s). Then, at the first run
    after an install, compile certkit's numba kernels once, ahead, before the test processes start: the workers load
    them from numba's cache instead of each compiling the same kernels when a test first calls them
    (certkit.models.kernel_warmup). Tests of a cold cache use a cache directory of their own."""
    if hasattr(config, "workerinput"):
        return
    config._certkit_cache = tempfile.mkdtemp(prefix="certkit-test-cache-")
    os.environ["XDG_CACHE_HOME"] = config._certkit_cache
    one_blas_thread()  # inherited by the workers (this process's BLAS is loaded already: it runs no tests with -n)
    _link_optvl_libraries()
    from certkit.models.kernel_warmup import compile_if_cold

    compile_if_cold(processes=2)


def _link_optvl_libraries():
    """The AVL peer (optvl, a test dependency) links its bundled BLAS folder as /tmp/optvl.libs when it first loads,
    if no such path exists: two test processes loading it at once race to create the link (one fails with
    FileExistsError), and a link left dangling by a removed installation makes every later load fail the same way.
    The controller makes the link once, before the workers start, to this installation's folder when it is missing or
    dangling (a link to another installation's existing folder is left alone)."""
    spec = importlib.util.find_spec("optvl")
    if spec is None or not spec.submodule_search_locations:
        return
    source = Path(spec.submodule_search_locations[0]).parent / "optvl.libs"
    link = Path("/tmp/optvl.libs")
    if not source.exists() or link.exists():
        return
    try:
        if link.is_symlink():  # dangling
            link.unlink()
        link.symlink_to(source)
    except OSError:
        pass  # another process made it meanwhile, or /tmp is not writable: optvl's own attempt decides


def pytest_unconfigure(config):
    folder = getattr(config, "_certkit_cache", None)
    if folder is not None:
        shutil.rmtree(folder, ignore_errors=True)


@pytest.fixture(scope="session")
def baseline():
    return load_aircraft(BASELINE)


@pytest.fixture
def ctx(baseline):
    return Context(baseline)


def count_conditions(monkeypatch, module, name: str) -> list:
    """``module.name`` — a function of (model, one row per condition, …): a run's x0, a trim's speeds — replaced by
    itself recording the number of conditions of each call: the list it fills."""
    calls: list = []
    function = getattr(module, name)

    def counting(model, rows, *args, **kwargs):
        calls.append(len(rows))
        return function(model, rows, *args, **kwargs)

    monkeypatch.setattr(module, name, counting)
    return calls


def clean_trims(aircraft, n: int):
    """The baseline's flight model and straight trims of ``n`` clean conditions: 0.7–1.0 MTOW at a 29.5 m CG,
    150–250 m/s TAS from sea level to 10 km."""
    import numpy as np

    from certkit.models.dynamics.trim import trim
    from certkit.models.flight import ROLES, control_limits, flight_model

    ctx = Context(aircraft)
    loadings = [ctx.loading(float(aircraft.model.mass.MTOW) * f, 29.5, "x") for f in np.linspace(0.7, 1.0, n)]
    model = flight_model(aircraft.model, ctx.aero("clean").model, loadings)
    speeds, heights = np.linspace(150, 250, n), np.linspace(0, 10000, n)
    return model, trim(model, speeds, heights, limits=control_limits(aircraft.model), roles=ROLES)


@pytest.fixture
def cli():
    runner = CliRunner()

    def invoke(*args):
        return runner.invoke(main, [str(a) for a in args], catch_exceptions=False)

    return invoke
