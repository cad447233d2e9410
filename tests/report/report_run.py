"""One small check of the baseline shared by the report tests: rules that fail (§25.161(d): the engine-out climb
needs more rudder than its design limit), comply, comply in part and are not evaluated (§25.173(b), (c) without a
control-force model), written once per test session."""

from __future__ import annotations

import functools
import json
import subprocess
import sys
from pathlib import Path

from tests.conftest import BASELINE, ROOT

SELECTION = "25.335,25.181,25.173,25.121(b),25.161"


@functools.lru_cache(maxsize=None)
def checked(folder: str, jobs: int = 1, select: str = SELECTION) -> tuple[Path, int]:
    """``certkit check`` of the baseline into ``folder`` (a subprocess, as a user runs it); (folder, exit code)."""
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "certkit.cli",
            "check",
            str(BASELINE),
            "--out",
            folder,
            "--select",
            select,
            "--jobs",
            str(jobs),
            "--quiet",
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert proc.returncode in (0, 1, 3), proc.stderr
    return Path(folder), proc.returncode


def results(folder: Path) -> dict:
    def refuse(constant):
        raise ValueError(f"{constant} in results.json")

    return json.loads((folder / "results.json").read_text(encoding="utf-8"), parse_constant=refuse)
