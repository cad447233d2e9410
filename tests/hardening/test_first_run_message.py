"""The first check after an install compiles certkit's numba kernels; the command says so instead of going quiet."""

import os
import subprocess
import sys

from click.testing import CliRunner

from certkit.cli.main import main

from ..conftest import ROOT


def test_an_empty_kernel_cache_is_seen_as_cold(tmp_path):
    probe = subprocess.run(
        [sys.executable, "-c", "from certkit.models.kernel_warmup import kernels_cached; print(kernels_cached())"],
        capture_output=True,
        text=True,
        env={**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)},
    )
    assert probe.stdout.strip() == "False", probe.stderr


def test_a_cold_kernel_cache_is_announced(tmp_path, monkeypatch):
    monkeypatch.setattr("certkit.models.kernel_warmup.kernels_cached", lambda: False)
    args = ["check", str(ROOT / "aircraft" / "lta.yaml"), "--select", "25.335(a)", "--out", str(tmp_path / "out")]
    announced = CliRunner().invoke(main, args)
    assert "compiling certkit's numba kernels" in announced.output
    quiet = CliRunner().invoke(main, [*args, "--quiet"])
    assert quiet.exit_code == announced.exit_code and "compiling" not in quiet.output
