"""SIGKILL at random moments leaves the report folder holding the previous complete set or the new one.

A set is complete when both files exist, results.json is strict JSON, and index.html has a section for exactly the
rules results.json lists (certkit.report.html.slug ids). Two levels: the set writer killed many times while it
replaces sets in a loop, and `certkit check` itself killed around the end of its run (where it writes).
"""

import json
import os
import random
import re
import signal
import subprocess
import sys
import time

from certkit.report.html import slug

from ..conftest import BASELINE, ROOT

_WRITER = """
import sys
from pathlib import Path
from certkit.report.output import write_set
out, i = Path(sys.argv[1]), 0
while True:
    i += 1
    tag = "AB"[i % 2]
    write_set(out, {"results.json": '{"tag": "%s", "pad": "%s"}' % (tag, "x" * 400000), "index.html": tag * 400000})
"""


def _writer_set(out) -> str:
    assert sorted(os.listdir(out)) == ["index.html", "results.json"], os.listdir(out)
    tag = json.loads((out / "results.json").read_text())["tag"]
    assert (out / "index.html").read_text() == tag * 400000
    return tag


def test_kill_while_sets_are_replaced(tmp_path):
    rng = random.Random(17)
    out = tmp_path / "out"
    seen = set()
    for _ in range(8):
        proc = subprocess.Popen([sys.executable, "-c", _WRITER, str(out)], cwd=ROOT)
        time.sleep(0.4 + rng.random() * 0.6)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        if out.exists():
            seen.add(_writer_set(out))
    assert seen  # the writer got to write (else the test proved nothing)


def _refuse(constant):
    raise ValueError(f"{constant} in results.json")


def _rule_set(out) -> tuple:
    assert sorted(os.listdir(out)) == ["index.html", "results.json"], os.listdir(out)
    ids = tuple(r["id"] for r in json.loads((out / "results.json").read_text(), parse_constant=_refuse)["rules"])
    sections = set(re.findall(r'<section class="rule" id="(r[0-9a-z-]+)"', (out / "index.html").read_text()))
    assert sections == {slug(i) for i in ids}
    return ids


def _check(out, select):
    return subprocess.Popen(
        [sys.executable, "-m", "certkit.cli", "check", str(BASELINE), "--select", select, "-j", "1", "--out", str(out)],
        cwd=ROOT,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )


def test_kill_certkit_check_keeps_a_complete_set(tmp_path):
    rng = random.Random(1717)
    out = tmp_path / "report"
    start = time.perf_counter()
    assert _check(out, "25.335(a)").wait(timeout=120) == 0
    duration = time.perf_counter() - start
    previous = _rule_set(out)
    assert previous == ("25.335(a)",)
    outcomes = []
    for _ in range(2):
        proc = _check(out, "25.335(b)")
        time.sleep(duration * (0.7 + 0.4 * rng.random()))  # around the end, where the report is written
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        outcomes.append(_rule_set(out))
    assert set(outcomes) <= {previous, ("25.335(b)",)}
