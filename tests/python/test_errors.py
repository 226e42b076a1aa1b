"""Bad input raises tpf.Error naming the file, line and field."""
import json

import numpy as np
import pytest

import tpf


def test_error_is_a_runtime_error():
    assert issubclass(tpf.Error, RuntimeError)


def test_missing_robot_file(tmp_path):
    path = tmp_path / "none.robot.json"
    with pytest.raises(tpf.Error) as e:
        tpf.Robot(str(path))
    assert e.value.file == str(path)
    assert str(path) in str(e.value)


def test_bad_friction_value_names_the_field(data, tmp_path):
    friction = json.loads((data / "arm4.friction.json").read_text())
    friction["viscous"][2] = -1.0
    path = tmp_path / "bad.friction.json"
    path.write_text(json.dumps(friction))
    with pytest.raises(tpf.Error) as e:
        tpf.load_stribeck_parameters(str(path))
    assert e.value.file == str(path)
    assert "viscous" in e.value.field
    assert e.value.message and e.value.message in str(e.value)


def test_unknown_parameter_file_field(data, tmp_path):
    params = json.loads((data / "arm4.params.json").read_text())
    params["frictoin"] = params.pop("friction")
    path = tmp_path / "bad.params.json"
    path.write_text(json.dumps(params))
    with pytest.raises(tpf.Error) as e:
        tpf.load_nominal_model(str(path), str(data / "arm4.robot.json"))
    assert e.value.file == str(path)
    assert "friction" in e.value.field


def test_bad_log_row_names_the_line_and_column(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("# tpf-log: 1\nt,q1,dq1,tau1\n0.0,0.1,0.0,1.0\n0.1,0.2,oops,1.0\n")
    with pytest.raises(tpf.Error) as e:
        tpf.read_log(str(path))
    assert e.value.file == str(path)
    assert e.value.line == 4
    assert "dq1" in str(e.value)


def test_infinite_value_is_not_written(tmp_path):
    log = tpf.Log(["t", "x"], np.array([[0.0, 1.0], [1.0, np.inf]]))
    with pytest.raises(tpf.Error):
        log.write(str(tmp_path / "inf.csv"))
