"""The robot model from Python: the dynamics identities, an independent Jacobian form of the
gravity torque and the mass matrix, finite differences of the kinematics, batches equal to
their samples, out= arrays, and the C++ core's own results to 1e-12."""
import os
import subprocess

import numpy as np
import pytest

import tpf


def child_env():
    """The environment of a child program: without the ASan runtime the sanitized build preloads
    into Python (the sanitized tools carry their own)."""
    return {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}

ROBOTS = ["arm4.robot.json", "real/kinova-gen3/gen3.robot.json"]


@pytest.fixture(scope="module", params=ROBOTS)
def robot(request, data):
    return tpf.Robot(str(data / request.param))


def states(robot, count, seed=1):
    rng = np.random.default_rng(seed)
    n = robot.joint_count
    return (rng.uniform(-2.5, 2.5, (count, n)), rng.uniform(-2, 2, (count, n)),
            rng.uniform(-4, 4, (count, n)))


def test_model_of_the_robot_file(data):
    arm = tpf.Robot(str(data / "arm4.robot.json"))
    assert arm.joint_count == 4
    assert len(arm.joint_names) == 4 and len(arm.link_names) == 5
    assert np.all(arm.lower < arm.upper)
    assert np.all(arm.gear_ratio > 1) and np.all(arm.torque_constant > 0)
    assert np.all(arm.armature > 0)
    np.testing.assert_array_equal(arm.gravity, [0, 0, -9.81])
    with pytest.raises(ValueError):
        arm.armature[0] = 1.0  # a view of the model, read-only
    gen3 = tpf.Robot(str(data / "real/kinova-gen3/gen3.robot.json"))
    assert gen3.joint_count == 7


def test_mass_matrix_is_symmetric_positive_definite(robot):
    q, _, _ = states(robot, 10)
    for M in robot.compute_mass_matrix(q):
        assert np.abs(M - M.T).max() < 1e-12
        assert np.linalg.eigvalsh(M).min() > 0


def test_rnea_is_mass_matrix_times_acceleration_plus_bias(robot):
    q, dq, ddq = states(robot, 10)
    zero = np.zeros_like(q)
    tau = robot.rnea(q, dq, ddq)
    bias = robot.rnea(q, dq, zero)
    M = robot.compute_mass_matrix(q)
    expected = np.einsum("sij,sj->si", M, ddq) + bias
    assert np.abs(tau - expected).max() < 1e-12 * (1 + np.abs(tau).max())
    np.testing.assert_allclose(robot.rnea(q, zero, zero), robot.compute_gravity(q), rtol=0,
                               atol=1e-12)


def test_forward_dynamics_inverts_rnea(robot):
    q, dq, ddq = states(robot, 10)
    ddq_back = robot.forward_dynamics(q, dq, robot.rnea(q, dq, ddq))
    assert np.abs(ddq_back - ddq).max() < 1e-9


def test_coriolis_matrix_gives_the_mass_matrix_derivative(robot):
    q, dq, _ = states(robot, 3)
    h = 1e-6
    for qs, dqs in zip(q, dq):
        C = robot.compute_coriolis_matrix(qs, dqs)
        M_dot = (robot.compute_mass_matrix(qs + h * dqs) -
                 robot.compute_mass_matrix(qs - h * dqs)) / (2 * h)
        assert np.abs(C + C.T - M_dot).max() < 1e-6 * (1 + np.abs(M_dot).max())


def link_jacobians(robot, q):
    """Jacobians of each link's centre of mass, from the module's kinematics."""
    poses = robot.forward_kinematics(q)
    for k in range(1, robot.joint_count + 1):
        R, p = poses[k, :3, :3], poses[k, :3, 3]
        com = R @ robot.com[k] + p
        yield k, R, robot.point_jacobian(q, k, com)


def test_gravity_and_mass_matrix_from_the_link_jacobians(robot):
    """G = −Σ m_k J_v,kᵀ g and M = Σ m_k J_vᵀJ_v + J_ωᵀ R I_c Rᵀ J_ω + diag(armature): other
    algorithms than the core's Newton–Euler and composite bodies."""
    q, _, _ = states(robot, 5, seed=4)
    g = robot.gravity
    for qs in q:
        G = np.zeros(robot.joint_count)
        M = np.diag(robot.armature)
        for k, R, J in link_jacobians(robot, qs):
            m, Jv, Jw = robot.mass[k], J[:3], J[3:]
            G -= m * Jv.T @ g
            M += m * Jv.T @ Jv + Jw.T @ R @ robot.inertia[k] @ R.T @ Jw
        assert np.abs(robot.compute_gravity(qs) - G).max() < 1e-12 * (1 + np.abs(G).max())
        assert np.abs(robot.compute_mass_matrix(qs) - M).max() < 1e-12 * (1 + np.abs(M).max())


def test_point_jacobian_is_the_derivative_of_the_kinematics(robot):
    q, _, _ = states(robot, 3, seed=2)
    n, h = robot.joint_count, 1e-6
    local = np.array([0.03, 0.01, -0.02])

    def point(qs):
        T = robot.forward_kinematics(qs)[n]
        return T[:3, :3] @ local + T[:3, 3]

    for qs in q:
        J = robot.point_jacobian(qs, n, point(qs))
        for i in range(n):
            e = np.zeros(n)
            e[i] = h
            v = (point(qs + e) - point(qs - e)) / (2 * h)
            assert np.abs(J[:3, i] - v).max() < 1e-8


def test_regressor_times_link_parameters_is_rnea(robot):
    """Y·π = RNEA + Coulomb + viscous friction, π built from the model's inertias."""
    q, dq, ddq = states(robot, 5, seed=3)
    n = robot.joint_count
    coulomb, viscous = np.linspace(0.1, 0.5, n), np.linspace(0.2, 0.9, n)
    pi = []
    for k in range(1, n + 1):
        m, c, Ic = robot.mass[k], robot.com[k], robot.inertia[k]
        Io = Ic + m * (c @ c * np.eye(3) - np.outer(c, c))
        pi.append([m, *(m * c), Io[0, 0], Io[0, 1], Io[0, 2], Io[1, 1], Io[1, 2], Io[2, 2]])
    pi = np.concatenate([np.ravel(pi), robot.armature, coulomb, viscous])
    Y = robot.compute_regressor(q, dq, ddq)
    assert Y.shape == (5, n, 13 * n)
    expected = robot.rnea(q, dq, ddq) + coulomb * np.sign(dq) + viscous * dq
    assert np.abs(Y @ pi - expected).max() < 1e-10 * (1 + np.abs(expected).max())


def test_batches_equal_their_samples(robot):
    q, dq, ddq = states(robot, 4, seed=5)
    for s in range(4):
        np.testing.assert_array_equal(robot.rnea(q, dq, ddq)[s], robot.rnea(q[s], dq[s], ddq[s]))
        np.testing.assert_array_equal(robot.compute_mass_matrix(q)[s],
                                      robot.compute_mass_matrix(q[s]))
        np.testing.assert_array_equal(robot.forward_kinematics(q)[s],
                                      robot.forward_kinematics(q[s]))
    # Lists and integer arrays are taken as float64.
    assert robot.compute_gravity(list(q[0])).shape == (robot.joint_count,)


def test_wrong_shapes_are_refused(robot):
    n = robot.joint_count
    with pytest.raises(ValueError, match=r"dq has shape \(3,\)"):
        robot.rnea(np.zeros(n), np.zeros(3), np.zeros(n))
    with pytest.raises(ValueError, match="unlike"):
        robot.rnea(np.zeros((2, n)), np.zeros((3, n)), np.zeros((2, n)))
    with pytest.raises(ValueError, match="link"):
        robot.point_jacobian(np.zeros(n), n + 1, np.zeros(3))


def test_out_arrays_and_inputs_numpy_does_not_hold_exactly(robot):
    q, dq, ddq = states(robot, 6, seed=4)
    n = robot.joint_count
    tau = robot.rnea(q[0], dq[0], ddq[0])
    out = np.full(n, np.nan)
    assert robot.rnea(q[0], dq[0], ddq[0], out=out) is out
    np.testing.assert_array_equal(out, tau)
    stacked = np.empty((6, n, n))
    assert robot.compute_mass_matrix(q, out=stacked) is stacked
    np.testing.assert_array_equal(stacked, robot.compute_mass_matrix(q))
    # Lists, float32, Fortran order and strided views are converted: the same numbers.
    np.testing.assert_array_equal(robot.rnea(list(q[0]), tuple(dq[0]), ddq[0]), tau)
    np.testing.assert_array_equal(robot.rnea(np.asfortranarray(q), dq, ddq), robot.rnea(q, dq, ddq))
    wide = np.zeros((6, 2 * n))
    wide[:, ::2] = q
    np.testing.assert_array_equal(robot.compute_gravity(wide[:, ::2]), robot.compute_gravity(q))
    assert robot.compute_gravity(q[0].astype(np.float32)).dtype == np.float64
    for bad in (np.empty(n + 1), np.empty(n, dtype=np.float32), np.empty((1, n)),
                np.empty(2 * n)[::2]):
        with pytest.raises(ValueError, match="out must be"):
            robot.rnea(q[0], dq[0], ddq[0], out=bad)
    frozen = np.empty(n)
    frozen.flags.writeable = False
    with pytest.raises(ValueError, match="out must be"):
        robot.rnea(q[0], dq[0], ddq[0], out=frozen)
    with pytest.raises(TypeError, match="q must be an array"):
        robot.rnea("joint angles", dq[0], ddq[0])
    with pytest.raises(ValueError, match="dq has shape"):
        robot.rnea(q[0], dq[0, :-1], ddq[0])


@pytest.mark.parametrize("name", ROBOTS)
def test_equals_the_cpp_core(name, data, tmp_path):
    """RNEA, gravity, M(q) and forward dynamics from Python against the same functions called
    from C++ (tests/python/dynamics_reference.cpp) on 20 random states, to 1e-12."""
    robot = tpf.Robot(str(data / name))
    q, dq, ddq = states(robot, 20, seed=7)
    n = robot.joint_count
    np.savetxt(tmp_path / "states.csv", np.hstack([q, dq, ddq]), delimiter=",", fmt="%.17g")
    subprocess.run(env=child_env(), args=[os.environ["TPF_DYNAMICS_REFERENCE"], str(data / name),
                    str(tmp_path / "states.csv"), str(tmp_path / "out.csv")], check=True)
    ref = np.loadtxt(tmp_path / "out.csv", delimiter=",", ndmin=2)
    assert ref.shape == (20, 1 + 3 * n + n * n) and np.all(ref[:, 0] == n)
    tau = robot.rnea(q, dq, ddq)
    parts = [tau, robot.compute_gravity(q), robot.compute_mass_matrix(q).reshape(20, n * n),
             robot.forward_dynamics(q, dq, tau)]
    column = 1
    for got in parts:
        want = ref[:, column:column + got.shape[1]]
        assert np.abs(got - want).max() <= 1e-12 * (1 + np.abs(want).max())
        column += got.shape[1]
