"""Benchmark: the first `certkit check aircraft/lta.yaml` after an install — numba compiling certkit's kernels into
an empty cache (a clean ``NUMBA_CACHE_DIR``) — against a warm run, as wall and CPU time of the whole process (the
CPU of the check and of its worker processes), and against another checkout of certkit in the same run
(``--against DIR``: its own source tree, run with this interpreter), alternating the two.

Run from the repository root:  python benchmarks/bench_first_run.py [--jobs 2] [--repeats 2] [--against DIR]
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))


#: the environment of the timed commands: bytecode written and read as an installed package has it (pip compiles the
#: modules when it installs them)
INSTALLED_ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def tree_env(tree: str, rules_path: str, cache: str) -> dict[str, str]:
    """The environment of a process of the checkout ``tree``: its certkit, its rules (:func:`rules_package`) and its
    own kernel cache, bytecode as installed."""
    return {**INSTALLED_ENV, "NUMBA_CACHE_DIR": cache, "PYTHONPATH": tree + os.pathsep + rules_path}


def run_check(tree: str, rules_path: str, cache: str, jobs: int) -> tuple[float, float]:
    """(wall s, CPU s of the process and its children) of one check of ``tree``'s baseline with its certkit."""
    env = tree_env(tree, rules_path, cache)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as out:
        subprocess.run(
            [
                sys.executable,
                "-m",
                "certkit.cli",
                "check",
                os.path.join(tree, "aircraft", "lta.yaml"),
                "--out",
                out,
                "--jobs",
                str(jobs),
                "--quiet",
            ],
            env=env,
            cwd=tree,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def rules_package(tree: str, folder: str) -> str:
    """A folder in which ``tree``'s rules import as ``certkit_rules`` (the installed package's name)."""
    os.symlink(os.path.join(tree, "rules"), os.path.join(folder, "certkit_rules"))
    return folder


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--against", help="another certkit checkout to time in the same run")
    args = parser.parse_args()
    trees = [("this code", ROOT)] + ([("--against", os.path.abspath(args.against))] if args.against else [])
    links = {name: rules_package(tree, tempfile.mkdtemp()) for name, tree in trees}
    results = {name: {"cold": [], "warm": []} for name, _ in trees}
    for _, tree in trees:  # untimed: each tree's modules compiled to bytecode, as an install leaves them
        folders = [os.path.join(tree, "certkit"), os.path.join(tree, "rules")]
        subprocess.run([sys.executable, "-m", "compileall", "-q", *folders], stdout=subprocess.DEVNULL, check=False)
    for _ in range(args.repeats):
        for name, tree in trees:
            with tempfile.TemporaryDirectory() as cache:
                results[name]["cold"].append(run_check(tree, links[name], cache, args.jobs))
                results[name]["warm"].append(run_check(tree, links[name], cache, args.jobs))
    for name, r in results.items():
        for kind in ("cold", "warm"):
            walls = ", ".join(f"{w:.1f}" for w, _ in r[kind])
            cpus = ", ".join(f"{c:.1f}" for _, c in r[kind])
            print(f"{name:>10} {kind}: wall {walls} s; CPU {cpus} s (--jobs {args.jobs})")
    if len(trees) == 2:
        (a, _), (b, _) = trees
        for kind in ("cold", "warm"):
            ratio = min(c for _, c in results[a][kind]) / min(c for _, c in results[b][kind])
            print(f"{kind} CPU, this code / --against: {ratio:.2f}")


if __name__ == "__main__":
    main()
