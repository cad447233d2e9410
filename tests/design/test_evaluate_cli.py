"""`certkit evaluate` from the command line: one record, bad input as exit 2 without a traceback."""

import json
import subprocess
import sys

import pytest

BASELINE = "aircraft/lta.yaml"


def _run(*args):
    return subprocess.run(
        [sys.executable, "-m", "certkit.cli", "evaluate", BASELINE, *args], capture_output=True, text=True
    )


@pytest.mark.parametrize(
    "args, expected",
    [
        (["--set", "geometry.horizontal_tail.aera=1200 ft^2"], "geometry.horizontal_tail.aera"),
        (["--set", "geometry.horizontal_tail.taper=1.5"], "less than or equal to 1"),
        (["--set", "geometry.horizontal_tail.area"], "PATH=VALUE"),
        (
            [
                "--set",
                "geometry.horizontal_tail.area=1343 ft^2",
                "--set",
                "geometry.horizontal_tail.aspect_ratio=5.54",
                "--set",
                "geometry.horizontal_tail.sweep_quarter_chord=41.78 deg",
                "--set",
                "geometry.horizontal_tail.taper=0.26",
            ],
            "behind the fuselage end",
        ),
    ],
)
def test_bad_design_is_exit_2_with_the_variable_named(args, expected):
    proc = _run(*args)
    assert proc.returncode == 2, proc.stderr
    assert expected in proc.stderr and "Traceback" not in proc.stderr


def test_one_record_as_json():
    """A restricted set of responses (only §25.171 among the non-loads rules) keeps the test short; the record is
    valid JSON (no NaN), names the design variable in SI and carries its sizing and rule results."""
    proc = _run(
        "--set",
        "geometry.horizontal_tail.area=1200 ft^2",
        "--response",
        "rule.25.171.margin",
        "--response",
        "sizing.*",
        "--json",
    )
    assert proc.returncode == 0, proc.stderr
    rec = json.loads(proc.stdout)
    assert rec["schema"] == "certkit.design-record/2"
    assert rec["variables"]["geometry.horizontal_tail.area"] == pytest.approx(1200 * 0.3048**2)
    assert set(rec["responses"]) >= {"rule.25.171.margin", "sizing.ht_group_mass_kg", "sizing.iterations"}
    assert not any(k.startswith("objective.cruise") for k in rec["responses"])  # the mission was not asked for
    assert rec["statuses"]["rule.25.171"] in ("complies", "fails", "not_evaluated")
