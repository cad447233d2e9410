"""Shared fixtures: the bundled baseline, a CLI runner and (tests/browser.py) the headless browser."""

from pathlib import Path

import pytest
from click.testing import CliRunner

from certkit.aircraft import load_aircraft
from certkit.cli.main import main
from certkit.engine.context import Context

#: the headless-browser fixture (``browser``) of the report tests
pytest_plugins = ["tests.browser"]

ROOT = Path(__file__).resolve().parents[1]
BASELINE = ROOT / "aircraft" / "lta.yaml"
SHARED_REFERENCE = ROOT.parent / "shared" / "reference"


def pytest_configure(config):
    """At the first run after an install, compile certkit's numba kernels once, ahead, before the test processes
    start (pytest-xdist's controller, or the lone process): the workers then load them from numba's cache instead of
    each compiling the same kernels when a test first calls them (certkit.models.kernel_warmup). Tests of a cold
    cache use a cache directory of their own."""
    if hasattr(config, "workerinput"):
        return
    from certkit.models.kernel_warmup import compile_if_cold

    compile_if_cold(processes=2)


@pytest.fixture(scope="session")
def baseline():
    return load_aircraft(BASELINE)


@pytest.fixture
def ctx(baseline):
    return Context(baseline)


@pytest.fixture
def cli():
    runner = CliRunner()

    def invoke(*args):
        return runner.invoke(main, [str(a) for a in args], catch_exceptions=False)

    return invoke
