"""Benchmark: certkit's vortex lattice against AVL 3.52 (optvl) on ~1000–1500-vortex geometries.

For each geometry, best of several repeats of
* ours, full derivative set: paneling, influence matrix, LU factorisation, all unit right-hand
  sides, force tensor, stability and control derivatives at one state;
* ours, a batch of 1000 force evaluations (``coefficients`` on 1000 states);
* optvl, full analysis: ``execute_run`` on a freshly loaded solver plus retrieval of the stability
  and control derivatives (same process, same geometry, fixed α).

The influence sums have two implementations with the same bits (:mod:`certkit.models.aero.vlm.biot_savart`): numpy
blocks while numba is not loaded (a lean ``certkit derivatives`` process) and numba loops once it is (a check, an
evaluation, a study worker). "ours full" is timed both ways: first without numba, then after importing it.

Run: ``python benchmarks/bench_vlm.py [--repeats 5]``.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from certkit.models.aero.interface import AeroState
from certkit.models.aero.vlm import VortexLattice, build_lattice
from certkit.models.aero.vlm.avl_file import read_avl, write_avl

ROOT = Path(__file__).resolve().parents[1]
REFERENCE = ROOT / ".." / "shared" / "reference" / "avl-b737"
sys.path.insert(0, str(ROOT))


def best_of(fn, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def ours_full(cfg, mach, alpha):
    vl = VortexLattice(cfg, mach=mach)
    vl.stability_derivatives(alpha=alpha)
    return vl


def optvl_full(avl_path: Path, mach: float, alpha_deg: float, repeats: int) -> float | None:
    try:
        from optvl import OVLSolver
    except ImportError:
        return None
    times = []
    cwd = os.getcwd()
    for _ in range(repeats):
        os.chdir(avl_path.parent)  # AVL opens airfoil files relative to the working directory
        try:
            solver = OVLSolver(geo_file=avl_path.name)
        finally:
            os.chdir(cwd)
        solver.set_parameter("Mach", mach)
        solver.set_constraint("alpha", "alpha", alpha_deg)
        t0 = time.perf_counter()
        solver.execute_run()
        solver.get_stab_derivs()
        solver.get_control_stab_derivs()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    from tests.aero.vlm_cases import transport

    cases = []
    tmp = Path(tempfile.mkdtemp(prefix="bench_vlm_"))
    if (REFERENCE / "b737.avl").is_file():
        cases.append(
            ("b737.avl (AVL sample)", read_avl(REFERENCE / "b737.avl"), (REFERENCE / "b737.avl").resolve(), 0.7)
        )
    tr = transport(mach=0.6, scale=1)
    for s in tr.surfaces:  # refine to about 1000 vortices
        s.n_chord = int(s.n_chord * 1.3)
        s.n_span = int(s.n_span * 1.3)
    cases.append(("generic transport", tr, write_avl(tr, tmp / "transport.avl"), 0.6))

    alpha = math.radians(2.0)
    rng = np.random.default_rng(0)
    rows = []
    for label, cfg, path, mach in cases:
        n = build_lattice(cfg).n_vortices
        # numba not loaded yet: the full set with the numpy influence sums
        t_full = best_of(lambda: ours_full(cfg, mach, alpha), args.repeats)  # noqa: B023  (called within this iteration)
        vl = ours_full(cfg, mach, alpha)
        state = AeroState(
            alpha=rng.uniform(-0.1, 0.2, 1000),
            beta=rng.uniform(-0.1, 0.1, 1000),
            p_hat=rng.uniform(-0.05, 0.05, 1000),
            q_hat=0.01,
            r_hat=0.0,
            mach=mach,
            controls={vl.control_names[0]: rng.uniform(-0.2, 0.2, 1000)},
        )
        t_batch = best_of(lambda: vl.coefficients(state), args.repeats)  # noqa: B023  (called within this iteration)
        t_avl = optvl_full(Path(path), mach, math.degrees(alpha), args.repeats)
        rows.append((label, n, t_full, t_batch, t_avl))

    import numba  # noqa: F401  (the compiled influence sums from here on)

    rows_numba = [best_of(lambda: ours_full(cfg, mach, alpha), args.repeats) for _, cfg, _, mach in cases]  # noqa: B023
    print(
        f"{'geometry':<24} {'vortices':>8} {'ours full, numpy (s)':>21} {'AVL/ours':>9} {'ours full, numba (s)':>21} "
        f"{'AVL/ours':>9} {'ours 1000 evals (s)':>20} {'optvl full (s)':>15}"
    )
    for (label, n, t_np, t_batch, t_avl), t_nb in zip(rows, rows_numba):
        r_np, r_nb = (f"{t_avl / t:9.2f}" if t_avl else "      n/a" for t in (t_np, t_nb))
        avl = f"{t_avl:15.3f}" if t_avl else "            n/a"
        print(f"{label:<24} {n:>8d} {t_np:>21.3f} {r_np} {t_nb:>21.3f} {r_nb} {t_batch:>20.4f} {avl}")


if __name__ == "__main__":
    main()
