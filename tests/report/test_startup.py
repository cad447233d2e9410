"""Start-up: `certkit rules` and `certkit explain` print metadata without loading the physics (numba, scipy, pint,
matplotlib, pandas); the rule index is rebuilt when a package file changes."""

from __future__ import annotations

import json
import os
import subprocess
import sys

from tests.conftest import ROOT

HEAVY = ("numba", "scipy", "pint", "matplotlib", "pandas", "numpy")
PROBE = """
import json, sys
from certkit.cli.main import main
try:
    main(sys.argv[1:], standalone_mode=False)
finally:
    print(json.dumps(sorted(m for m in {heavy!r} if m in sys.modules)), file=sys.stderr)
"""


def _loaded(args, cache) -> tuple[list[str], str]:
    env = {**os.environ, "XDG_CACHE_HOME": str(cache)}
    proc = subprocess.run(
        [sys.executable, "-c", PROBE.format(heavy=HEAVY), *args], capture_output=True, text=True, cwd=ROOT, env=env
    )
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stderr.strip().splitlines()[-1]), proc.stdout


def test_rules_and_explain_load_no_heavy_library(tmp_path):
    first, listing = _loaded(["rules"], tmp_path)  # builds the index: imports the rules once
    assert "numba" in first
    again, listing_again = _loaded(["rules"], tmp_path)
    assert again == [] and listing_again == listing and "25.121(b)" in listing
    loaded, text = _loaded(["explain", "§25.337"], tmp_path)
    assert loaded == [] and text.startswith("§25.337  Limit maneuvering load factors")
    loaded, text = _loaded(["explain", "§ 25.331(c)(2)"], tmp_path)
    assert loaded == [] and text.startswith("§25.331(c)(2)")


def test_index_follows_the_package_files(tmp_path, monkeypatch):
    from certkit.engine import rule_index

    pkg = tmp_path / "pkg"
    pkg.mkdir()
    module = pkg / "r.py"
    module.write_text("x = 1\n")
    monkeypatch.setattr(rule_index, "_package_folders", lambda: [pkg])
    before = rule_index.index_key()
    module.write_text("x = 22\n")  # another size
    assert rule_index.index_key() != before
    os.utime(module, ns=(1, 1))
    changed = rule_index.index_key()
    os.utime(module, ns=(2, 2))  # same size, another modification time
    assert rule_index.index_key() != changed


def test_explain_matches_ids_with_and_without_section_sign():
    from certkit.engine.rule_index import find

    meta = [{"id": "25.121(a)", "symbol": "a"}, {"id": "25.121(b)", "symbol": "b"}, {"id": "25.1211", "symbol": "c"}]
    assert [m["id"] for m in find(meta, "§25.121(b)")] == ["25.121(b)"]
    assert [m["id"] for m in find(meta, "b")] == ["25.121(b)"]
    assert [m["id"] for m in find(meta, "§ 25.121(")] == ["25.121(a)", "25.121(b)"]
