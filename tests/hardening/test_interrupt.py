"""Ctrl-C exits 130 leaving the previous report whole; worker processes end with the coordinator, also when
it is killed (reproducers: SIGINT exited 1; workers were alive 111 s after the coordinator's SIGKILL)."""

import os
import signal
import subprocess
import sys
import time

import pytest

from ..conftest import BASELINE, ROOT

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc for the worker processes")


def _workers(pid: int) -> list[int]:
    out = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                stat = open(f"/proc/{entry}/stat").read()
            except OSError:
                continue
            if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
                out.append(int(entry))
    return out


def _alive(pid: int) -> bool:
    try:
        return open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def _started_check(out):
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "certkit.cli",
            "check",
            str(BASELINE),
            "--select",
            "25.33,25.34",
            "-j",
            "2",
            "--out",
            str(out),
        ],
        cwd=ROOT,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    deadline = time.monotonic() + 90
    while time.monotonic() < deadline and len(_workers(proc.pid)) < 2 and proc.poll() is None:
        time.sleep(0.1)
    workers = _workers(proc.pid)
    assert len(workers) >= 2, "the check did not start its worker processes"
    return proc, workers


def _gone(workers, within=5.0) -> bool:
    deadline = time.monotonic() + within
    while time.monotonic() < deadline and any(map(_alive, workers)):
        time.sleep(0.1)
    return not any(map(_alive, workers))


def test_sigint_exits_130_and_keeps_the_previous_report(tmp_path):
    out = tmp_path / "report"
    out.mkdir()
    (out / "results.json").write_text('{"previous": true}')
    (out / "index.html").write_text("previous")
    proc, workers = _started_check(out)
    proc.send_signal(signal.SIGINT)
    assert proc.wait(timeout=30) == 130
    stderr = proc.stderr.read()
    assert "interrupted" in stderr and "Traceback" not in stderr
    assert _gone(workers)
    assert (out / "results.json").read_text() == '{"previous": true}' and (out / "index.html").read_text() == "previous"


def test_workers_end_when_the_coordinator_is_killed(tmp_path):
    proc, workers = _started_check(tmp_path / "report")
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)
    assert _gone(workers)


def test_an_interrupt_swallowed_on_its_way_up_still_stops_the_outputs(tmp_path, monkeypatch):
    """A KeyboardInterrupt lost in a finaliser or a callback (the check then runs on) must not let the new set replace
    the previous one: the recorded interrupt is raised again before any output is written."""
    from certkit import interrupts
    from certkit.report.output import write_set

    out = tmp_path / "report"
    out.mkdir()
    (out / "results.json").write_text('{"previous": true}')
    monkeypatch.setitem(interrupts._state, "requested", False)
    with pytest.raises(KeyboardInterrupt):
        try:
            interrupts.on_interrupt(signal.SIGINT, None)
        except KeyboardInterrupt:
            pass  # swallowed, as a finaliser does
        write_set(out, {"results.json": '{"new": true}'})
    assert (out / "results.json").read_text() == '{"previous": true}'
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".certkit-")]
