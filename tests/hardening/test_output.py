"""Outputs: one consistent set replaced in one step, no symlink followed, paths checked first, folder names
distinct per aircraft name."""

import json
import os

import pytest

from certkit.engine.results import Condition, Finding, RuleResult, RunResult
from certkit.errors import UserError
from certkit.report.output import prepare_output, report_folder_name, write_set


def _set(tag: str) -> dict:
    return {"results.json": json.dumps({"run": tag}), "index.html": f"<p>{tag}</p>"}


def _read(out) -> tuple:
    return json.loads((out / "results.json").read_text())["run"], (out / "index.html").read_text()


def test_set_replaces_the_previous_one_whole(tmp_path):
    out = tmp_path / "reports" / "a"
    write_set(prepare_output(out), _set("one"))
    write_set(prepare_output(out), _set("two"))
    assert _read(out) == ("two", "<p>two</p>")
    assert sorted(os.listdir(out.parent)) == ["a"]  # no temporary folder left beside it


def test_symlink_inside_the_output_folder_is_not_followed(tmp_path):
    """Reproducer: out/results.json -> ../victim.txt overwrote the victim."""
    victim = tmp_path / "victim.txt"
    victim.write_text("precious")
    out = tmp_path / "out"
    write_set(prepare_output(out), _set("one"))
    (out / "results.json").unlink()
    (out / "results.json").symlink_to("../victim.txt")
    write_set(prepare_output(out), _set("two"))
    assert victim.read_text() == "precious"
    assert not (out / "results.json").is_symlink() and _read(out)[0] == "two"


def test_foreign_files_in_the_folder_are_kept(tmp_path):
    """--out naming a folder with other files: only the report files are replaced (each one whole)."""
    out = tmp_path / "mine"
    out.mkdir()
    (out / "notes.txt").write_text("keep")
    (out / "index.html").symlink_to(tmp_path / "victim.html")
    (tmp_path / "victim.html").write_text("precious")
    write_set(prepare_output(out), _set("one"))
    assert (out / "notes.txt").read_text() == "keep" and _read(out) == ("one", "<p>one</p>")
    assert (tmp_path / "victim.html").read_text() == "precious"


def test_stale_temporary_folders_of_dead_runs_are_removed(tmp_path):
    stale = tmp_path / ".certkit-999999999-abc.new"  # no such process
    stale.mkdir()
    write_set(prepare_output(tmp_path / "out"), _set("one"))
    assert not stale.exists()


@pytest.mark.parametrize(
    "make, words",
    [
        (lambda t: (t / "dangling").symlink_to(t / "nowhere") or t / "dangling", "does not exist"),
        (lambda t: t / ("x" * 300), "too long"),
        (lambda t: (t / "file").write_text("") or t / "file" / "out", "is a file"),
        (lambda t: (t / "file2").write_text("") or t / "file2", "not a folder"),
    ],
)
def test_bad_output_paths_are_user_errors(tmp_path, make, words):
    with pytest.raises(UserError, match=words):
        prepare_output(make(tmp_path))


def test_symlink_to_a_folder_is_honoured(tmp_path):
    real = tmp_path / "real"
    real.mkdir()
    (tmp_path / "link").symlink_to(real)
    write_set(prepare_output(tmp_path / "link"), _set("one"))
    assert (tmp_path / "link").is_symlink() and _read(real)[0] == "one"


@pytest.mark.parametrize(
    "names",
    [
        ("日本語", "中文", ".", "..", ""),
        ("a\x00b", "a\nb", "a b", "a_b", "a/b"),
        ("LTA 777", "LTA-777", "lta_777", "x" * 300, "x" * 301),
    ],
)
def test_folder_names_are_distinct_and_safe(names):
    slugs = [report_folder_name(n) for n in names]
    assert len(set(slugs)) == len(slugs), slugs
    for s in slugs:
        assert s not in (".", "..") and "/" not in s and "\x00" not in s and s.isprintable()
        assert 0 < len(s.encode()) <= 255
    assert report_folder_name("日本語") == "日本語"  # letters of any script are kept as they are


def test_plain_names_are_kept_as_they_are():
    assert report_folder_name("LTA-777_200ER") == "LTA-777_200ER"


def test_results_json_has_no_nan_or_infinity():
    finding = Finding(
        Condition(mass=float("nan")), "c", "not_evaluated", value=float("inf"), details={"x": [float("nan")]}
    )
    run = RunResult("v", "n", "s", "p", "c", [RuleResult("1", "s", "t", [finding])], models={"m": {"v": float("-inf")}})
    text = run.to_json()

    def refuse(constant):
        raise ValueError(constant)

    data = json.loads(text, parse_constant=refuse)
    assert data["non_finite_numbers"]["count"] == 4
    assert data["rules"][0]["findings"][0]["value"] is None
