"""The declared airplane's sizing baseline kept in the user's cache (:mod:`certkit.design.baseline_store`): a process
that loads it evaluates a design to the same record, bit for bit, as one that computed it; the entry follows
everything the baseline is computed from."""

import json
import os
import subprocess
import sys

import pytest

from certkit.design import baseline_store
from certkit.design.sizing_loop import sizing_rules
from certkit.engine.registry import DiscoveryOptions, discover

from ..conftest import ROOT

DESIGN = {"geometry.horizontal_tail.area": "1150 ft^2", "geometry.horizontal_tail.taper": 0.3}

# one design in a fresh process; with "forbid", computing the baseline is an error (it must come from the store)
SCRIPT = """
import json, sys
from certkit.design import sizing_loop
if sys.argv[1] == "forbid":
    def computed(*args, **kwargs):
        raise AssertionError("the baseline was computed, not loaded")
    sizing_loop._baseline_value = computed
from certkit.design.evaluate import evaluate_design
record = evaluate_design("aircraft/lta.yaml", json.loads(sys.argv[2]))
record.pop("timings")
print(json.dumps(record, sort_keys=True))
"""


def _evaluate(cache, mode):
    env = {**os.environ, "XDG_CACHE_HOME": str(cache)}
    done = subprocess.run(
        [sys.executable, "-c", SCRIPT, mode, json.dumps(DESIGN)], capture_output=True, text=True, env=env, cwd=ROOT
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout


def test_a_stored_baseline_gives_the_record_of_a_computed_one(tmp_path):
    computed = _evaluate(tmp_path, "compute")
    assert len(list((tmp_path / "certkit" / "baselines").glob("*.pickle"))) == 1
    loaded = _evaluate(tmp_path, "forbid")
    assert loaded == computed


@pytest.fixture(scope="module")
def chosen(baseline):
    return sizing_rules(discover(DiscoveryOptions())).rules


def test_the_key_follows_what_the_baseline_is_computed_from(baseline, chosen, monkeypatch):
    """Another declared airplane, another certkit, another rules package, other sizing rules or another BLAS thread
    setting: another entry."""
    key = baseline_store.entry_key(baseline.model, chosen)
    heavier = baseline.model.model_copy(update={"mass": baseline.model.mass.model_copy(update={"MZFW": 1.0})})
    assert baseline_store.entry_key(heavier, chosen) != key
    assert baseline_store.entry_key(baseline.model, chosen[1:]) != key
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "7")
    assert baseline_store.entry_key(baseline.model, chosen) != key
    monkeypatch.undo()
    assert baseline_store.entry_key(baseline.model, chosen) == key
    monkeypatch.setattr(baseline_store, "source_digest", lambda: "another certkit")
    assert baseline_store.entry_key(baseline.model, chosen) != key
    monkeypatch.undo()
    monkeypatch.setattr(baseline_store, "_package_digest", lambda module: "another rules package")
    assert baseline_store.entry_key(baseline.model, chosen) != key


def test_the_rules_package_digest_reads_every_module_of_it(chosen, tmp_path, monkeypatch):
    """The bundled rules' package is found (not "unknown"); a package's digest changes with any of its modules (a
    support module its rules import included), not only the rule's own."""
    packages = {r.__module__.split(".")[0] for r in chosen}
    assert len(packages) == 1 and baseline_store._package_digest(packages.pop()) != "unknown"
    package = tmp_path / "plugin_rules_probe"
    (package / "support").mkdir(parents=True)
    (package / "__init__.py").write_text("")
    (package / "rule.py").write_text("from plugin_rules_probe.support import helper\n")
    (package / "support" / "__init__.py").write_text("")
    (package / "support" / "helper.py").write_text("LIMIT = 2.5\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    import plugin_rules_probe.rule  # noqa: F401

    before = baseline_store._package_digest("plugin_rules_probe.rule")
    (package / "support" / "helper.py").write_text("LIMIT = 3.8\n")
    assert baseline_store._package_digest("plugin_rules_probe.rule") != before


# two designs of the declared geometry (a structural setting only) in one process; prints the lattice solves, then
# each record
SAME_GEOMETRY = """
import json, sys
from certkit.engine import context
solves = []
solve = context.lattice_derivatives
context.lattice_derivatives = lambda *a, **k: solves.append(1) or solve(*a, **k)
from certkit.design.evaluate import evaluate_design
records = []
for strain in (0.0038, 0.0042):
    record = evaluate_design("aircraft/lta.yaml", {"sizing.horizontal_tail.material.design_strain": strain})
    record.pop("timings")
    records.append(record)
print(len(solves))
print(json.dumps(records, sort_keys=True))
"""


def test_designs_of_the_declared_geometry_share_one_lattice_with_a_stored_baseline(tmp_path):
    """A design that changes no geometry flies on the declared airplane's lattice. With the baseline computed in the
    process, that is the baseline pass's; loaded from the store (without its context), the first such design's serves
    the next: one lattice solve in the process either way, and the same records."""
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path)}

    def run():
        done = subprocess.run([sys.executable, "-c", SAME_GEOMETRY], capture_output=True, text=True, env=env, cwd=ROOT)
        assert done.returncode == 0, done.stderr[-3000:]
        solves, records = done.stdout.splitlines()
        return int(solves), records

    computed = run()
    loaded = run()
    assert computed[0] == 1 and loaded[0] == 1
    assert loaded[1] == computed[1]
