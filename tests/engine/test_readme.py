"""The README's commands are the ones CI runs, the documented examples run verbatim, and the rule table of
docs/rules.md is current."""

import re

from click.testing import CliRunner

from certkit.cli.main import main

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
    assert table in (ROOT / "docs" / "rules.md").read_text()


DOCUMENTED = ("README.md", "docs/usage.md")


def sh_blocks():
    return [
        block
        for name in DOCUMENTED
        for block in re.findall(r"```sh\n(.*?)\n```", (ROOT / name).read_text(), flags=re.S)
    ]


def test_every_readme_example_runs_verbatim(tmp_path):
    """Each line of the `sh` blocks of the README and the usage page, run by bash from the repository root as written:
    exit 0, or 1/3 for a
    check or diff whose verdict is a failure or something not evaluated; never a usage error or a traceback."""
    import os
    import subprocess

    lines = [ln for block in sh_blocks() for ln in block.splitlines() if ln.strip() and not ln.startswith("#")]
    assert len(lines) >= 10 and any("examples/lta-clean.avl" in ln for ln in lines)
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path / "cache")}
    bindir = os.path.dirname(os.path.realpath(__import__("sys").executable))
    env["PATH"] = bindir + os.pathsep + env.get("PATH", "")  # the certkit of this environment
    from concurrent.futures import ThreadPoolExecutor

    def run(line):
        return line, subprocess.run(
            ["bash", "-c", line], cwd=ROOT, env=env, capture_output=True, text=True, timeout=300
        )

    later = [ln for ln in lines if ln.startswith("certkit diff")]  # reads what the checks before it wrote
    with ThreadPoolExecutor(max_workers=2) as pool:  # two at a time: the machine's cores
        done = list(pool.map(run, [ln for ln in lines if ln not in later])) + [run(ln) for ln in later]
    for line, proc in done:
        allowed = {0, 1, 3} if line.startswith(("certkit check", "certkit diff")) else {0}
        assert proc.returncode in allowed, f"{line}\nexit {proc.returncode}\n{proc.stderr[-2000:]}"
        assert "Traceback" not in proc.stderr and "error:" not in proc.stderr, f"{line}\n{proc.stderr[-2000:]}"
