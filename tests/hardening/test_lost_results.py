"""Ways to lose or misread a result: a rule that ends the program, a diff that hides a change, a report folder that
eats the user's data, and ordinary mistakes that must be a message and exit 2 (never exit 0, never an internal
error, never a wait for ever).

Reference: the expectations are certkit's documented exit codes (certkit/cli.py: 0 all comply, 1 fails, 2 input or
usage error, 3 not evaluated, 70 internal error) and the bounds the aircraft file's schema declares.
"""

from __future__ import annotations

import json
import os
import sqlite3
import subprocess
import sys
import textwrap
import time

import pytest

from certkit.aircraft import json_schema, validate_aircraft_data
from certkit.aircraft.yaml_source import source_from_text
from certkit.errors import InputError, UserError
from certkit.report.output import prepare_output, write_set

from ..conftest import BASELINE
from .mutate import with_value, write_yaml

EXITING_RULE = textwrap.dedent("""
    import sys

    from certkit.engine.conditions import CgCorners, ConditionSpace
    from certkit.engine.registry import Rule, rule

    {module_level}

    @rule
    class ExitingRule(Rule):
        id = "25.902"
        symbol = "user-exiting-rule"
        title = "User rule that ends the program"
        amendment = "none"
        requirement = "None."
        margin = "None."
        conditions = ConditionSpace(loading=CgCorners())

        def evaluate(self, ctx, conditions, crit):
            sys.exit(0)
""")


def _certkit(*args, cwd=None, timeout=120):
    return subprocess.run(
        [sys.executable, "-m", "certkit.cli", *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=timeout
    )


def _user_error(result, *words):
    assert result.returncode == 2, (result.returncode, result.stderr)
    assert "Traceback" not in result.stderr and "internal error" not in result.stderr
    for word in words:
        assert word in result.stderr, result.stderr


# --- a rule plugin that calls sys.exit -----------------------------------------------------------------------------


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_rule_calling_sys_exit_is_an_error_naming_the_rule(tmp_path, jobs):
    folder = tmp_path / "rules"
    folder.mkdir()
    (folder / "exiting.py").write_text(EXITING_RULE.format(module_level=""))
    select = "25.902" if jobs == "1" else "25.902,25.335(a)"  # two rules: evaluated in worker processes
    result = _certkit("check", BASELINE, "--rules", folder, "--select", select, "--out", tmp_path / "out", "-j", jobs)
    _user_error(result, "25.902", str(folder), "sys.exit(0)")
    assert not (tmp_path / "out").exists()


def test_rule_module_calling_sys_exit_on_import_is_an_error_naming_the_file(tmp_path):
    folder = tmp_path / "rules"
    folder.mkdir()
    (folder / "exiting.py").write_text(EXITING_RULE.format(module_level="sys.exit(0)"))
    _user_error(_certkit("rules", "--rules", folder), "exiting.py", "sys.exit(0)")


# --- certkit diff ---------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("tolerance", ["nan", "-1e-6", "inf"])
def test_diff_refuses_a_tolerance_that_hides_or_invents_changes(tmp_path, tolerance):
    results = tmp_path / "results.json"
    results.write_text("{}")
    _user_error(_certkit("diff", results, results, "--tolerance", tolerance), "--tolerance", tolerance)


def test_diff_of_a_binary_file_is_a_user_error(tmp_path):
    binary = tmp_path / "results.json"
    binary.write_bytes(bytes(range(256)) * 4)
    _user_error(_certkit("diff", binary, binary), str(binary), "not a results.json")


# --- the report folder ----------------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["results.json", "index.html"])
def test_user_folder_named_like_a_report_file_is_never_deleted(tmp_path, name):
    out = tmp_path / "out"
    (out / name).mkdir(parents=True)
    (out / name / "my-notes.txt").write_text("keep me")
    start = time.perf_counter()
    _user_error(_certkit("check", BASELINE, "--out", out, "-j", "1"), str(out / name), "will not delete")
    assert time.perf_counter() - start < 90  # refused before the evaluation (a full check at -j 1: minutes)
    assert (out / name / "my-notes.txt").read_text() == "keep me"


def test_user_folder_appearing_during_the_evaluation_is_not_deleted(tmp_path):
    out = prepare_output(tmp_path / "out")
    write_set(out, {"results.json": "{}", "index.html": "<p>first</p>"})
    (out / "results.json").unlink()
    (out / "results.json").mkdir()
    (out / "results.json" / "data.csv").write_text("1,2")
    with pytest.raises(UserError, match="will not delete"):
        write_set(out, {"results.json": "{}", "index.html": "<p>second</p>"})
    assert (out / "results.json" / "data.csv").read_text() == "1,2"


# --- ordinary mistakes: exit 2 with a message -----------------------------------------------------------------------


def test_evaluate_on_a_missing_file(tmp_path):
    _user_error(_certkit("evaluate", tmp_path / "missing.yaml"), "missing.yaml", "not found")


def test_output_file_into_a_missing_folder_is_refused_before_the_evaluation(tmp_path):
    start = time.perf_counter()
    result = _certkit(
        "check",
        BASELINE,
        "--out",
        tmp_path / "out",
        "--output-format",
        "sarif",
        "--output-file",
        tmp_path / "nowhere" / "certkit.sarif",
        "-j",
        "1",
    )
    _user_error(result, "--output-file", "nowhere", "does not exist")
    assert time.perf_counter() - start < 90  # a full check at -j 1 takes minutes
    assert not (tmp_path / "out").exists()  # nothing was evaluated nor written


@pytest.mark.parametrize(
    "option, value", [("--alpha", "inf"), ("--alpha", "nan"), ("--beta", "-inf"), ("--mach", "nan")]
)
def test_derivatives_refuses_non_finite_angles(option, value):
    _user_error(_certkit("derivatives", BASELINE, option, value), option, "finite")


def test_trim_refuses_a_non_finite_bank():
    _user_error(_certkit("trim", BASELINE, "--bank", "nan"), "--bank", "finite")


@pytest.mark.parametrize("option", ["--select", "--ignore"])
@pytest.mark.parametrize("value", ["", " , "])
def test_empty_rule_pattern_is_refused_not_read_as_every_rule(tmp_path, option, value):
    result = _certkit("check", BASELINE, option, value, "--out", tmp_path / "out")
    _user_error(result, option, "names no rule")
    assert not (tmp_path / "out").exists()


def test_fifo_as_the_aircraft_file_is_refused_without_waiting(tmp_path):
    fifo = tmp_path / "aircraft.yaml"
    os.mkfifo(fifo)
    result = _certkit("check", fifo, "--out", tmp_path / "out", timeout=60)
    _user_error(result, str(fifo), "not a regular file", "FIFO")


def test_a_device_as_the_aircraft_file_is_refused(tmp_path):
    _user_error(_certkit("check", "/dev/zero", "--out", tmp_path / "out"), "/dev/zero", "not a regular file")


@pytest.mark.parametrize("page", [2, 4, 6])
def test_study_store_with_a_malformed_page_is_a_user_error(tmp_path, page):
    """A store whose b-tree page (the meta table, the cases table, an index) was overwritten: SQLite reads it as
    "database disk image is malformed" — a damaged file to restore, not a bug of certkit."""
    from certkit.study.runner import run_study
    from certkit.study.spec import load_study
    from certkit.study.store import Store
    from tests.study.conftest import EVALUATORS, write_study

    study = write_study(tmp_path, lhs=30)
    store = tmp_path / "small.sqlite"
    with Store.open(store, create=True) as db:
        run_study(load_study(study), db, "serial", evaluator=f"{EVALUATORS}:analytic")
    connection = sqlite3.connect(store)
    connection.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    page_size = connection.execute("PRAGMA page_size").fetchone()[0]
    connection.close()
    raw = bytearray(store.read_bytes())
    start = (page - 1) * page_size + 8  # past the page header: its cell pointers
    raw[start : start + 256] = b"\xff" * 256
    store.write_bytes(bytes(raw))
    for command in (["study", "status", store], ["study", "export", store, "--format", "csv"]):
        _user_error(_certkit(*command), str(store), "restore it from a copy")


# --- values the loader accepted that distort results: refused with their bounds -------------------------------------


@pytest.mark.parametrize(
    "path, value, words",
    [
        ("geometry.wing.taper", 1e-30, "greater than or equal to 0.02"),
        ("geometry.horizontal_tail.taper", 0.0, "greater than or equal to 0.02"),
        ("configurations.takeoff.delta_CD0", -12000, "greater than or equal to 0"),
        ("configurations.landing.delta_CD0", 12.0, "less than 0.3"),
        ("configurations.approach.flap", "-20 deg", "greater than or equal to 0"),
        ("configurations.landing.flap", "120 deg", "less than or equal to 1.22"),
        ("mass.passengers", -0.0, "integer"),
        ("mass.passengers", 305.5, "integer"),
    ],
)
def test_physically_meaningless_values_are_located_errors(tmp_path, path, value, words):
    data = with_value(path, value)
    text = write_yaml(tmp_path, data).read_text()
    with pytest.raises(InputError) as err:
        validate_aircraft_data(data, source_from_text(text, "aircraft.yaml"))
    found = {p.path: p for p in err.value.problems}
    assert path in found, list(found)
    problem = found[path]
    assert words in problem.message
    assert problem.line is not None and problem.line > 1  # where: the line of the value in the file
    assert problem.value == value or (isinstance(value, float) and str(problem.value) == str(value))
    assert path.rsplit(".", 1)[-1] in str(err.value)


def test_the_schema_documents_the_bounds():
    defs = json_schema()["$defs"]
    configuration = defs["Configuration"]["properties"]
    assert configuration["delta_CD0"]["minimum"] == 0.0 and configuration["delta_CD0"]["exclusiveMaximum"] == 0.3
    flap = configuration["flap"]
    assert "0 (retracted) to 70 deg" in flap["description"]  # a quantity with a unit: its bounds in words
    assert defs["LiftingSurface"]["properties"]["taper"]["minimum"] == 0.02
    assert "whole number" in json.dumps(defs["MassProperties"]["properties"]["passengers"])
