"""The README's commands are the ones CI runs, and its rule table is current."""

import re

from click.testing import CliRunner

from certkit.cli import main

from ..conftest import ROOT


def bash_blocks():
    return re.findall(r"```bash\n(.*?)\n```", (ROOT / "README.md").read_text(), flags=re.S)


def test_quickstart_has_exactly_two_setup_commands_and_ci_runs_the_test_one():
    blocks = bash_blocks()
    assert len(blocks) == 2
    assert "certkit check aircraft/lta.yaml" in blocks[0]
    assert "pytest" in blocks[1]
    ci = (ROOT / ".ci" / "run").read_text()
    assert blocks[1].strip() in ci.splitlines()


def test_rule_table_is_current():
    table = CliRunner().invoke(main, ["rules", "--markdown"]).output.strip()
    assert table in (ROOT / "README.md").read_text()
