"""Benchmark: one design evaluation (`certkit evaluate`), whole command and in-process, with the cost split.

1. The whole command on the baseline, `certkit evaluate aircraft/lta.yaml` (subprocess: imports, sizing loop,
   every rule, mission), best of 3 — the issue's target is under 10 s on the 2-core machine.
2. In one process, the baseline and a few redesigned tails one after the other (what a study worker does): per
   design the split read from the record's timings — set-up (variables, validation), each sizing iteration
   (Subpart C horizontal-tail loads rules and the box sizing), the other rules, the mission.

The numba kernels are compiled (or loaded from their disk cache) by a first, untimed run; the command runs with its
modules' bytecode cached, as an installed package does (``PYTHONDONTWRITEBYTECODE`` unset for it).
With ``--against DIR`` (another checkout of certkit, e.g. the code before a change): the CPU per redesigned tail of
both trees in pairs of processes run at the same time, one per core, so that the host's drift (its speed can change
by 10 % within minutes) falls on both; each process evaluates a warm-up design, settles its garbage collector as a
study worker does, then the redesigned tails twice. Prints each pair's ratio and their median.
With ``--against DIR --alternate N``: N designs of the seed study's plan (``bench_study.py``'s sample, another seed),
each evaluated by a process of each tree pinned to the same core, in ABBA order (this code first on even designs, the
other first on odd ones), on every core at once (the designs shared out between the cores): the two codes meet the
same host speed design by design and the same place, so a change of a few per cent shows where whole runs drift by
more. Prints the CPU of each design for both codes, the ratio of the sums and the median of the per-design ratios.

Run from the repository root:  python benchmarks/bench_evaluate.py [--against DIR [--pairs N | --alternate N]]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from bench_first_run import INSTALLED_ENV, ROOT, rules_package, tree_env  # noqa: E402

BASELINE = os.path.join(os.path.dirname(__file__), "..", "aircraft", "lta.yaml")
DESIGNS = [
    {},
    {"geometry.horizontal_tail.area": "1000 ft^2", "geometry.horizontal_tail.aspect_ratio": 4.2},
    {
        "geometry.horizontal_tail.area": "1250 ft^2",
        "geometry.horizontal_tail.sweep_quarter_chord": "32 deg",
        "geometry.horizontal_tail.controls.elevator.chord_ratio": 0.32,
    },
    {
        "geometry.horizontal_tail.taper": 0.28,
        "geometry.horizontal_tail.thickness_ratio": 0.1,
        "geometry.horizontal_tail.controls.elevator.span_end": 0.98,
    },
]


def command(repeats: int = 3) -> list[float]:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run(
            [sys.executable, "-m", "certkit.cli", "evaluate", BASELINE, "--json"],
            env=INSTALLED_ENV,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            check=True,
        )
        times.append(time.perf_counter() - t0)
    return times


def in_process():
    t0 = time.perf_counter()
    from certkit.design.evaluate import evaluate_design

    print(f"imports {time.perf_counter() - t0:.2f} s")
    for values in DESIGNS:
        t0 = time.perf_counter()
        rec = evaluate_design(BASELINE, values)
        wall = time.perf_counter() - t0
        t = rec["timings"]
        its = ", ".join(f"{s:.2f}" for s in t.get("sizing_iteration_s", []))
        print(
            f"{wall:6.2f} s  set-up {t['setup_s']:.2f} | sizing {t['sizing_s']:.2f} ({its}; aero models "
            f"{t['aero_setup_s']:.2f}) | other rules "
            f"{t['rules_s']:.2f} | mission {t.get('mission_s', 0.0):.2f}   {values or 'baseline'}"
        )


#: a paired process: a warm-up design, the collector settled as a study worker settles it
#: (:func:`certkit.study.worker._freeze_long_lived`), then the redesigned tails twice; prints the CPU per design
PAIRED_PROCESS = """
import gc, json, sys, time
from certkit.design.evaluate import evaluate_design
baseline, designs = sys.argv[1], json.loads(sys.argv[2])
evaluate_design(baseline, designs[0])
gc.collect(); gc.freeze(); gc.set_threshold(20_000, *gc.get_threshold()[1:])
t0 = time.process_time()
for values in designs * 2:
    evaluate_design(baseline, values)
print(f"{(time.process_time() - t0) / (2 * len(designs)):.4f}")
"""


def _trees(against: str) -> tuple[dict[str, str], dict[str, dict[str, str]]]:
    """This checkout and ``against`` by name, and each one's process environment: its own source tree, rules and
    kernel cache, one BLAS thread."""
    trees = {"this code": ROOT, "--against": os.path.abspath(against)}
    envs = {
        name: {**tree_env(tree, rules_package(tree, tempfile.mkdtemp()), tempfile.mkdtemp()), "OMP_NUM_THREADS": "1"}
        for name, tree in trees.items()
    }
    return trees, envs


def paired(against: str, pairs: int) -> None:
    """CPU per redesigned tail of this code and of the checkout ``against`` (its own source tree, rules and kernel
    cache; this interpreter), in ``pairs`` pairs of processes run at the same time."""
    trees, envs = _trees(against)
    redesigned = json.dumps(DESIGNS[1:])

    def start(name: str) -> subprocess.Popen:
        baseline = os.path.join(trees[name], "aircraft", "lta.yaml")
        return subprocess.Popen(
            [sys.executable, "-c", PAIRED_PROCESS, baseline, redesigned],
            env=envs[name],
            cwd=tempfile.gettempdir(),
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            text=True,
        )

    for name in trees:  # untimed, one after the other: bytecode written, kernels compiled into each tree's cache
        start(name).communicate()
    ratios = []
    for _ in range(pairs):
        procs = {name: start(name) for name in trees}
        cpu = {name: float(p.communicate()[0].split()[-1]) for name, p in procs.items()}
        ratios.append(cpu["this code"] / cpu["--against"])
        print(
            f"  CPU per design: this code {cpu['this code']:.3f} s, --against {cpu['--against']:.3f} s, "
            f"{ratios[-1]:.3f}×"
        )
    print(f"this code / --against (median of {pairs} pairs run at the same time): {statistics.median(ratios):.3f}")


#: an alternating process: a warm-up design, the collector settled as a study worker settles it, then a design per
#: line of its standard input (its index), evaluated with the collector paused as a study worker pauses it; prints
#: each design's CPU seconds ("nan" for an impossible planform)
ALTERNATING_PROCESS = """
import gc, json, sys, time
from certkit.design.evaluate import evaluate_design
baseline, designs = sys.argv[1], json.loads(sys.argv[2])
evaluate_design(baseline, designs[0])
gc.collect(); gc.freeze()
print("ready", flush=True)
for line in sys.stdin:
    gc.disable(); t0 = time.process_time()
    try:
        evaluate_design(baseline, designs[int(line)]); cpu = time.process_time() - t0
    except Exception:
        cpu = float("nan")
    gc.enable(); gc.collect()
    print(cpu, flush=True)
"""


def alternate(against: str, count: int) -> None:
    """CPU per design of this code and of the checkout ``against`` on ``count`` designs of the seed study, each design
    by a process of each code pinned to the same core, in ABBA order, every core at once."""
    from bench_study import STUDY, sample

    from certkit.study.executors import available_cores
    from certkit.study.plan import DEFAULT_EVALUATOR
    from certkit.study.spec import load_study

    cores = sorted(os.sched_getaffinity(0))[: available_cores()]
    designs, _ = sample(load_study(STUDY), DEFAULT_EVALUATOR, count + 1, seed=51)
    trees, envs = _trees(against)
    text = json.dumps(designs)

    def start(name: str, core: int) -> subprocess.Popen:
        return subprocess.Popen(
            [sys.executable, "-c", ALTERNATING_PROCESS, os.path.join(trees[name], "aircraft", "lta.yaml"), text],
            env=envs[name],
            cwd=tempfile.gettempdir(),
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            text=True,
            preexec_fn=lambda: os.sched_setaffinity(0, {core}),
        )

    for name in trees:  # untimed, one after the other: bytecode written, kernels compiled into each tree's cache
        start(name, cores[0]).communicate("")
    cpu: dict[str, dict[int, float]] = {name: {} for name in trees}

    def drive(k: int, core: int) -> None:
        procs = {name: start(name, core) for name in trees}
        for p in procs.values():
            if p.stdout.readline().strip() != "ready":
                raise RuntimeError("an alternating process did not start")
        for turn, i in enumerate(range(1 + k, count + 1, len(cores))):
            for name in list(trees)[:: 1 if turn % 2 == 0 else -1]:
                procs[name].stdin.write(f"{i}\n")
                procs[name].stdin.flush()
                cpu[name][i] = float(procs[name].stdout.readline())
        for p in procs.values():
            p.communicate("")

    with ThreadPoolExecutor(len(cores)) as pool:
        list(pool.map(drive, range(len(cores)), cores))
    done = [i for i in sorted(cpu["this code"]) if not math.isnan(cpu["this code"][i] + cpu["--against"][i])]
    for i in done:
        a, b = cpu["this code"][i], cpu["--against"][i]
        print(f"  design {i:3d}: this code {a:.3f} s, --against {b:.3f} s CPU, {a / b:.3f}×")
    a, b = (sum(cpu[name][i] for i in done) for name in trees)
    ratios = [cpu["this code"][i] / cpu["--against"][i] for i in done]
    print(
        f"this code / --against over {len(done)} designs alternated on {len(cores)} core(s): CPU per design "
        f"{a / len(done):.3f} against {b / len(done):.3f} s, ratio of the sums {a / b:.3f}, median per design "
        f"{statistics.median(ratios):.3f}"
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--against", help="another certkit checkout: pairs of processes of both, at the same time")
    parser.add_argument("--pairs", type=int, default=4)
    parser.add_argument(
        "--alternate", type=int, metavar="N", help="with --against: N designs in all, alternated on every core"
    )
    args = parser.parse_args()
    if args.alternate and not args.against:
        parser.error("--alternate compares with another checkout: give --against DIR")
    if args.against and args.alternate:
        alternate(args.against, args.alternate)
        return
    if args.against:
        paired(args.against, args.pairs)
        return
    command(repeats=1)  # compiles the kernels or loads them from the cache
    times = command()
    print(f"certkit evaluate aircraft/lta.yaml: best {min(times):.2f} s of {', '.join(f'{x:.2f}' for x in times)}")
    print("\nin one process (a study worker), per design:")
    in_process()


if __name__ == "__main__":
    main()
