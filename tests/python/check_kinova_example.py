"""examples/python/kinova_residual.py run headless on a short setting (one fitting file, one
held-out file of the MEASURED Kinova Gen3 logs): it writes its PNG, and the figures it prints
are those of `tpf identify` + `tpf validate --json` on the same files. Run by the ctest
python_example (not collected with the module's tests: it needs matplotlib)."""
import json
import os
import pathlib
import re
import subprocess
import sys

import pytest

EXAMPLE = pathlib.Path(__file__).parents[2] / "examples/python/kinova_residual.py"
FIT, HELD_OUT = "RunTrajectory1.csv.gz", "opti_traj_testing2.csv.gz"


def test_example_prints_the_cli_figures_and_writes_the_png(data, tmp_path):
    png = tmp_path / "residual.png"
    run = subprocess.run([sys.executable, str(EXAMPLE), "--fit", FIT, "--held-out", HELD_OUT,
                          "--out", str(png)], check=True, capture_output=True, text=True,
                         env=dict(os.environ, MPLBACKEND="Agg"))
    assert png.stat().st_size > 10000 and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    printed = {int(j): (float(b), float(a)) for j, b, a in
               re.findall(r"joint (\d): before ([\d.]+) after ([\d.]+) N·m", run.stdout)}
    assert sorted(printed) == [1, 2, 3, 4, 5, 6]  # joint 7's sensor is flat
    assert "joint 7: no usable sensor" in run.stdout

    logs = data / "real/kinova-gen3/logs"
    robot = str(data / "real/kinova-gen3/gen3.robot.json")
    params, report = tmp_path / "cli.params.json", tmp_path / "cli.validate.json"
    tool = os.environ["TPF_CLI"]
    subprocess.run([tool, "identify", "--log", str(logs / FIT), "--robot", robot, "--out",
                    str(params), "--quiet"], check=True, capture_output=True)
    subprocess.run([tool, "validate", "--params", str(params), "--robot", robot, "--log",
                    str(logs / HELD_OUT), "--json", str(report)], check=True, capture_output=True)
    sensor = json.loads(report.read_text())["sensor_rmse_newton_metre"]
    for j, (before, after) in printed.items():
        assert before == pytest.approx(sensor[j - 1]["kt_only"]["all"], abs=1e-6)
        assert after == pytest.approx(sensor[j - 1]["estimates"][0]["all"], abs=1e-6)
        assert after < before  # identification lowers the residual on every scored joint
