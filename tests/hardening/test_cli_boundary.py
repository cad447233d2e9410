"""The CLI boundary: user errors exit 2 with a message, anything unexpected is an internal error (exit 70)
with a bug-report hint and a traceback only with --debug; bad outputs are refused before the evaluation."""

import subprocess
import sys
import time

import pytest
from click.testing import CliRunner

import certkit.aircraft
from certkit.cli.main import EXIT_INTERNAL, main

from ..conftest import BASELINE
from .mutate import with_value, write_yaml


def _certkit(*args, cwd=None, timeout=120):
    return subprocess.run(
        [sys.executable, "-m", "certkit.cli", *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=timeout
    )


@pytest.fixture
def broken_schema(monkeypatch):
    def fail():
        raise ZeroDivisionError("division by zero")

    monkeypatch.setattr(certkit.aircraft, "json_schema", fail)


def test_unexpected_exception_is_an_internal_error_without_traceback(broken_schema):
    result = CliRunner().invoke(main, ["schema"])
    assert result.exit_code == EXIT_INTERNAL not in (1, 2)
    assert "internal error: ZeroDivisionError" in result.output and "report it" in result.output
    assert "Traceback" not in result.output


def test_debug_shows_the_traceback(broken_schema):
    result = CliRunner().invoke(main, ["--debug", "schema"])
    assert result.exit_code == EXIT_INTERNAL
    assert "Traceback" in result.output


@pytest.mark.parametrize(
    "path, value",
    [
        ("mass.MTOW", "10**1000 lb"),
        ("mass.inertia.Ixz", float("nan")),
        ("mass.components.0.inertia.Iyy", "inf kg*m^2"),
        ("criteria", {"25.999": {"justification": "no such rule here", "values": {"x": 1}}}),
    ],
)
def test_reproducers_exit_2_without_traceback(tmp_path, path, value):
    result = _certkit("check", write_yaml(tmp_path, with_value(path, value)), "--out", tmp_path / "out", "-j", "1")
    assert result.returncode == 2, result.stderr
    assert "Traceback" not in result.stderr and "Warning" not in result.stderr
    assert path.split(".")[0] in result.stderr
    assert not (tmp_path / "out").exists()


def test_unknown_rule_in_criteria_names_the_known_ones(tmp_path):
    data = with_value(
        "criteria",
        {
            "25.999": {"justification": "no such rule here", "values": {"x": 1}},
            "25.337": {"justification": "an unknown criterion", "values": {"nope": 1.0}},
        },
    )
    result = _certkit("check", write_yaml(tmp_path, data), "--out", tmp_path / "out")
    assert result.returncode == 2
    assert "no rule 25.999" in result.stderr and "25.337" in result.stderr
    assert "no criterion 'nope'" in result.stderr and "n_positive_floor" in result.stderr


@pytest.mark.parametrize("out", ["file/out", "dangling", "x" * 300])
def test_bad_output_refused_before_the_evaluation(tmp_path, out):
    (tmp_path / "file").write_text("")
    (tmp_path / "dangling").symlink_to(tmp_path / "nowhere")
    start = time.perf_counter()
    result = _certkit("check", BASELINE, "--out", out, cwd=tmp_path)
    assert result.returncode == 2, result.stderr
    assert "--out" in result.stderr and "Traceback" not in result.stderr
    assert time.perf_counter() - start < 20  # no rule was evaluated (a full check takes minutes)


def test_dev_zero_is_a_user_error(tmp_path):
    result = _certkit("check", "/dev/zero", "--out", tmp_path / "out")
    assert result.returncode == 2 and "not a regular file" in result.stderr and "Traceback" not in result.stderr


def test_evaluate_checks_the_overrides_too(tmp_path):
    """`certkit evaluate` (and so every study case) refuses an override of an unknown rule before it sizes anything."""
    data = with_value("criteria", {"25.999": {"justification": "no such rule here", "values": {"x": 1}}})
    result = _certkit("evaluate", write_yaml(tmp_path, data))
    assert result.returncode == 2, result.stderr
    assert "no rule 25.999" in result.stderr and "Traceback" not in result.stderr
