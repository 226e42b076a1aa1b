#!/usr/bin/env python3
"""The Python module's overhead over C++, both measured in one run (docs/python.md, "Overhead"):
runs tpf_python_bench (Google Benchmark, the C++ side), then the same calls from Python, and
prints the figures, the difference and the ratio. CPU time on both sides (process time), so that
other processes on the machine weigh less.

    PYTHONPATH=build/release/python taskset -c 1 python3 bench/python/python_overhead.py \\
        --bench build/release/bin/tpf_python_bench [--seconds 3600]
"""
import argparse
import json
import os
import pathlib
import statistics
import subprocess
import time
import timeit

import numpy as np

import tpf

DATA = pathlib.Path(__file__).resolve().parents[2] / "data"


def arguments():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--bench", required=True, help="the tpf_python_bench program")
    p.add_argument("--seconds", type=float, default=3600.0, help="length of the replayed log [s]")
    p.add_argument("--repetitions", type=int, default=5, help="of each measurement (median)")
    return p.parse_args()


def cpp_figures(a):
    """Median CPU time of the C++ RNEA [ns] and of the replay [s]."""
    run = subprocess.run(
        [a.bench, "--benchmark_format=json", f"--benchmark_repetitions={a.repetitions}",
         "--benchmark_report_aggregates_only=true"], check=True, capture_output=True, text=True,
        env=dict(os.environ, TPF_BENCH_REPLAY_SECONDS=str(a.seconds)))
    medians = {b["run_name"]: b for b in json.loads(run.stdout)["benchmarks"]
               if b.get("aggregate_name") == "median"}
    rnea = next(b for name, b in medians.items() if name.startswith("BM_RneaGen3Dynamic"))
    replay = next(b for name, b in medians.items() if name.startswith("BM_ReplayEstimator"))
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
    return (rnea["cpu_time"] * scale[rnea["time_unit"]] * 1e9,
            replay["cpu_time"] * scale[replay["time_unit"]])


def python_rnea(repetitions, calls=200000):
    """Median CPU time of one tpf.Robot.rnea call [ns]: new result, and into out=."""
    robot = tpf.Robot(str(DATA / "real/kinova-gen3/gen3.robot.json"))
    q, dq, ddq, out = np.zeros(7), np.ones(7), np.ones(7), np.empty(7)
    rnea = robot.rnea
    figures = []
    for call in ("rnea(q, dq, ddq)", "rnea(q, dq, ddq, out)"):
        timer = timeit.Timer(call, globals=locals(), timer=time.process_time)
        figures.append(statistics.median(timer.repeat(repetitions, calls)) / calls * 1e9)
    return figures


def synthetic_motion(seconds, joints=4):
    """The log tpf_python_bench builds: t_k = k/400 s; joint j at ω_j = 2π(0.2 + 0.1j):
    q = 0.5 sin ωt, q̇ = 0.5 ω cos ωt, τ = 2 sin(ωt + 0.3) [N·m]."""
    t = np.arange(round(seconds * 400.0)) / 400.0
    w = 2 * np.pi * (0.2 + 0.1 * np.arange(joints))
    return {"t": t, "q": 0.5 * np.sin(np.outer(t, w)), "dq": 0.5 * w * np.cos(np.outer(t, w)),
            "tau": 2 * np.sin(np.outer(t, w) + 0.3)}


def python_replay(seconds, repetitions):
    """Median CPU time of tpf.estimate over the synthetic log [s] (files read each time, as the
    C++ side does)."""
    motion = synthetic_motion(seconds)
    files = dict(params=str(DATA / "arm4.params.json"), robot=str(DATA / "arm4.robot.json"))
    options = dict(estimator=str(DATA / "arm4.estimator.json"),
                   weights=str(DATA / "weights/arm4.tcn.json"))
    times = []
    for _ in range(repetitions):
        start = time.process_time()
        trace = tpf.estimate(motion, files["params"], files["robot"], **options)
        times.append(time.process_time() - start)
        del trace
    return statistics.median(times), len(motion["t"])


def main():
    a = arguments()
    cpp_rnea, cpp_replay = cpp_figures(a)
    py_rnea, py_rnea_out = python_rnea(a.repetitions)
    py_replay, rows = python_replay(a.seconds, min(a.repetitions, 3))
    print("SIMULATED inputs; CPU time, medians of", a.repetitions, "repetitions")
    print(f"RNEA, 7-DoF Kinova Gen3: C++ {cpp_rnea:.0f} ns; Python {py_rnea:.0f} ns "
          f"(+{py_rnea - cpp_rnea:.0f} ns), into out= {py_rnea_out:.0f} ns "
          f"(+{py_rnea_out - cpp_rnea:.0f} ns); target: at most 1000 ns above C++")
    print(f"estimator over {a.seconds:.0f} s at 400 Hz ({rows} samples, arm4, per-joint TCN): "
          f"C++ {cpp_replay:.2f} s; Python {py_replay:.2f} s; ratio {py_replay / cpp_replay:.3f}; "
          f"target: at most 1.2")


if __name__ == "__main__":
    main()
