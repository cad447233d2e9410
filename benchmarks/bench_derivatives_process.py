"""Benchmark: the whole ``certkit derivatives FILE.avl`` process against AVL's whole process (optvl) on one file.

Both are started as new Python processes, as a user runs them, with BLAS pinned to one thread
(``OMP_NUM_THREADS=OPENBLAS_NUM_THREADS=MKL_NUM_THREADS=1``): interpreter start, imports, reading the geometry, the
lattice solution and the stability and control derivatives at one state, printing. One warm-up run each, then
``--repeats`` runs of each, alternating (a shared machine's load changes between runs; alternating lets both see
the same), best of each.

Bytecode: an installed package (pip) carries its compiled modules, so by default both processes read and write
theirs in one fresh folder (``PYTHONPYCACHEPREFIX``; the warm-up run fills it) with ``PYTHONDONTWRITEBYTECODE``
unset. ``--inherit-bytecode`` keeps the caller's settings instead: where ``PYTHONDONTWRITEBYTECODE=1`` is set, an
editable install of certkit compiles its own modules at every start (about 0.03 s) while optvl's installed ones
are read compiled.

Run: ``python benchmarks/bench_derivatives_process.py [--file examples/lta-clean.avl] [--repeats 5]``.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
AVL_SCRIPT = """
import os, sys
from optvl import OVLSolver
path, mach, alpha = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
os.chdir(os.path.dirname(os.path.abspath(path)))
solver = OVLSolver(geo_file=os.path.basename(path))
solver.set_parameter("Mach", mach)
solver.set_constraint("alpha", "alpha", alpha)
solver.execute_run()
derivs = solver.get_stab_derivs()
controls = solver.get_control_stab_derivs()
print(len(derivs), len(controls))
"""


def timed(cmd: list[str], env: dict) -> float:
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, env=env, cwd=ROOT, capture_output=True, text=True)
    elapsed = time.perf_counter() - t0
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed:\n{proc.stderr}")
    return elapsed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--file", default=str(ROOT / "examples" / "lta-clean.avl"))
    parser.add_argument("--mach", type=float, default=0.7)
    parser.add_argument("--alpha", type=float, default=1.9)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument(
        "--inherit-bytecode",
        action="store_true",
        help="keep the caller's PYTHONDONTWRITEBYTECODE / PYTHONPYCACHEPREFIX (default: one fresh cache)",
    )
    args = parser.parse_args()
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
    ours = [
        sys.executable,
        "-m",
        "certkit.cli",
        "derivatives",
        args.file,
        "--mach",
        str(args.mach),
        "--alpha",
        str(args.alpha),
    ]
    avl = [sys.executable, "-c", AVL_SCRIPT, args.file, str(args.mach), str(args.alpha)]
    commands = {"certkit derivatives": ours, "AVL (optvl) process": avl}
    with tempfile.TemporaryDirectory(prefix="bench-pycache-") as cache:
        if not args.inherit_bytecode:
            env.pop("PYTHONDONTWRITEBYTECODE", None)
            env["PYTHONPYCACHEPREFIX"] = cache
        for cmd in commands.values():
            timed(cmd, env)  # warm-up: bytecode, page cache
        times = {name: [] for name in commands}
        for _ in range(args.repeats):
            for name, cmd in commands.items():
                times[name].append(timed(cmd, env))
    rows = [(name, min(t)) for name, t in times.items()]
    bytecode = "caller's bytecode settings" if args.inherit_bytecode else "bytecode cached for both"
    for name, t in rows:
        print(f"{name:<24} {t:7.3f} s (best of {args.repeats}, alternating, whole process, {bytecode})")
    ratio = rows[1][1] / rows[0][1]
    print(f"certkit / AVL: {'%.2f× faster' % ratio if ratio >= 1 else '%.2f× slower' % (1 / ratio)}")


if __name__ == "__main__":
    main()
