"""Benchmark: certkit batch RK4 vs JSBSim on the same 737.

A batch of 240 conditions (8 CG positions × 30 speed–altitude points) of JSBSim's 737 rebuilt as a
certkit model (tests/dynamics/jsbsim_737.py) is trimmed, then flies a 10 s manoeuvre (elevator
doublet, 1° for 1 s each way, plus a 2° aileron pulse) at 100 Hz with RK4. JSBSim flies one such
10 s manoeuvre in the same process (output disabled, ``run()`` in a loop, dt = 0.01 s).

Throughput = simulated seconds × conditions per wall second, timed on a second call (the first one
compiles the numba kernels, or loads them from the disk cache; its time is printed too). Run from
the repository root:
    python benchmarks/bench_dynamics.py
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from certkit.models.dynamics.eom import AircraftModel  # noqa: E402
from certkit.models.dynamics.simulate import Doublet, Pulse, simulate  # noqa: E402
from certkit.models.dynamics.trim import trim  # noqa: E402
from tests.dynamics.jsbsim_737 import build_737, jsbsim_cruise  # noqa: E402

T_END, DT = 10.0, 0.01


def jsbsim_run():
    fdm = jsbsim_cruise()
    fdm.set_dt(DT)
    fdm.disable_output()
    n = int(round(T_END / DT))
    t0 = time.perf_counter()
    for k in range(n):
        t = k * DT
        fdm["fcs/elevator-cmd-norm"] = (
            (1.0 if 1.0 <= t < 2.0 else -1.0 if 2.0 <= t < 3.0 else 0.0) * np.radians(1) / 0.3
        )
        fdm["fcs/aileron-cmd-norm"] = (np.radians(2) / 0.35) if 4.0 <= t < 5.0 else 0.0
        fdm.run()
    return time.perf_counter() - t0, fdm


def certkit_batch(fdm):
    base, V0, h0 = build_737(fdm)
    n_cg, n_pts = 8, 30
    cg_x = base.cg[0, 0] + np.linspace(-0.6, 0.6, n_cg)
    V = np.linspace(0.85, 1.1, n_pts) * V0
    h = np.linspace(h0 - 2000.0, h0 + 1500.0, n_pts)
    cg = np.repeat(base.cg, n_cg * n_pts, axis=0)
    cg[:, 0] = np.repeat(cg_x, n_pts)
    model = AircraftModel(base.aero, base.mass[0], cg, base.inertia[0], base.engines, g=base.g, n=n_cg * n_pts)
    Vb, hb = np.tile(V, n_cg), np.tile(h, n_cg)
    t0 = time.perf_counter()
    tb = trim(model, Vb, hb)
    t_trim = time.perf_counter() - t0
    inputs = {"elevator": Doublet(1.0, 1.0, np.radians(1.0)), "aileron": Pulse(4.0, 1.0, np.radians(2.0))}
    t0 = time.perf_counter()
    res = simulate(model, tb.x, tb.u, T_END, DT, inputs=inputs, record_every=1)
    t_sim = time.perf_counter() - t0
    return model.n, t_trim, t_sim, tb, res


def main():
    t_js, fdm = jsbsim_run()
    fdm = jsbsim_cruise()
    t0 = time.perf_counter()
    certkit_batch(fdm)  # first call: numba compiles the kernels (or loads them from its disk cache)
    t_first = time.perf_counter() - t0
    n, t_trim, t_sim, tb, res = certkit_batch(fdm)
    print(f"certkit first call (compilation or cache load included): {t_first:.2f} s")
    thr_js = T_END / t_js
    thr_ck = T_END * n / t_sim
    print(f"JSBSim 737, one condition: {T_END:.0f} s simulated in {t_js:.3f} s wall -> {thr_js:,.0f} sim-s/s")
    print(
        f"certkit, {n} conditions: trim {t_trim:.3f} s ({int(tb.converged.sum())}/{n} converged), "
        f"RK4 {T_END:.0f} s at {1 / DT:.0f} Hz in {t_sim:.3f} s -> {thr_ck:,.0f} condition-sim-s/s"
    )
    print(
        f"ratio certkit/JSBSim: {thr_ck / thr_js:.1f}x (target >= 10x); trim target < 1 s: "
        f"{'met' if t_trim < 1.0 else 'NOT met'}"
    )
    print(f"peak n_z over the batch {res['n_z'].max():.3f}, min {res['n_z'].min():.3f}")


if __name__ == "__main__":
    main()
