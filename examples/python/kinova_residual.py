#!/usr/bin/env python3
"""MEASURED Kinova Gen3 logs (W. Chiha, MIT licence, data/real/kinova-gen3/SOURCE.md): identify
the nominal model on the fitting files, validate it on held-out files, and plot the current-based
joint torque against the joint torque sensor before (K_t·i alone) and after identification
(K_t·i less the identified drive loss d = friction + I_a·q̈), as `tpf identify` and
`tpf validate` compute them.

    PYTHONPATH=build/release/python python3 examples/python/kinova_residual.py --out residual.png

Prints one line per joint, "joint J: before B after A N·m" (RMSE over the held-out files, every
regime), the same numbers as `tpf validate --json`'s sensor_rmse_newton_metre (kt_only, and
estimates[0]), and writes the figure (matplotlib, Agg backend: no display needed)."""
import argparse
import os
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import tpf  # noqa: E402

DATA = pathlib.Path(os.environ.get("TPF_DATA_DIR", pathlib.Path(__file__).parents[2] / "data"))
KINOVA = DATA / "real/kinova-gen3"
FIT = ["RunTrajectory1.csv.gz", "Trajectory1.csv.gz", "RecordTrajectory_quadratic.csv.gz"]
HELD_OUT = ["opti_traj_testing1.csv.gz", "opti_traj_testing2.csv.gz"]


def arguments():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--fit", nargs="+", default=FIT, help="fitting files in data/real/kinova-gen3/logs")
    p.add_argument("--held-out", nargs="+", default=HELD_OUT, help="held-out files, scored")
    p.add_argument("--out", default="kinova_residual.png", help="PNG to write")
    p.add_argument("--params", help="also write the identified parameter file here")
    return p.parse_args()


def drive_loss(model, log, t):
    """d = friction(q̇, |G(q)|) + I_a·q̈ [N·m] per sample: the part of K_t·i the sensor behind the
    gear does not see. q̈ by central differences of q̇ smoothed over 15 ms (the plot's curve only;
    the printed figures are validate's, with its own q̈ filter)."""
    dq = np.asarray(log.dq)
    kernel = np.ones(15) / 15
    smooth = np.column_stack([np.convolve(dq[:, j], kernel, mode="same")
                              for j in range(dq.shape[1])])
    ddq = np.gradient(smooth, t, axis=0)
    _, friction = model.predict_effort(np.asarray(log.q), dq, ddq)
    armature = np.zeros(model.joint_count)
    for name, value in zip(model.base_names, model.base_values):
        if name.startswith("Ia"):
            armature[int(name[2:]) - 1] = value
    return friction + armature * ddq


def plot(model, robot, held_out, scores, path):
    log = tpf.read_log(str(held_out[-1]))
    t = log.t - log.t[0]
    before = log.torque(robot) - log.tau_sensor
    after = before - drive_loss(model, log, log.t)
    fig, (bars, series) = plt.subplots(2, 1, figsize=(9, 7))
    joints = np.arange(1, model.joint_count + 1)
    bars.bar(joints - 0.2, [s[0] for s in scores], 0.4, label="before: K_t·i")
    bars.bar(joints + 0.2, [s[1] for s in scores], 0.4, label="after identification: K_t·i − d")
    bars.set(xlabel="joint", ylabel="RMSE against the torque sensor [N·m]",
             title="MEASURED Kinova Gen3 (W. Chiha, MIT): held-out files, every regime")
    bars.legend()
    joint = int(np.nanargmax([s[0] - s[1] for s in scores]))
    series.plot(t, before[:, joint], lw=0.6, label="before: K_t·i − τ_sensor")
    series.plot(t, after[:, joint], lw=0.6, label="after: K_t·i − d − τ_sensor")
    series.set(xlabel=f"time [s], {pathlib.Path(str(held_out[-1])).name}",
               ylabel=f"joint {joint + 1} residual [N·m]")
    series.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    a = arguments()
    logs = KINOVA / "logs"
    robot_file = str(KINOVA / "gen3.robot.json")
    fit = [str(logs / f) for f in a.fit]
    held_out = [str(logs / f) for f in a.held_out]
    identified = tpf.identify(fit, robot_file)
    if a.params:
        identified.save(a.params)
    model = identified.nominal
    validation = tpf.validate(model, held_out)
    print(f"MEASURED: identified on {', '.join(a.fit)}; scored on {', '.join(a.held_out)}")
    scores = []
    for j, s in enumerate(validation["sensor_rmse_newton_metre"]):
        if s["samples"] == 0:
            print(f"joint {j + 1}: no usable sensor")
            scores.append((np.nan, np.nan))
            continue
        scores.append((s["kt_only"]["all"], s["estimates"][0]["all"]))
        print(f"joint {j + 1}: before {scores[-1][0]:.6f} after {scores[-1][1]:.6f} N·m "
              f"({s['samples']} samples)")
    plot(model, tpf.Robot(robot_file), held_out, scores, a.out)
    print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
