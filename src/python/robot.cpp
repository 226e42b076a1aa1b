// tpf.Robot: a robot file's model (joints, limits, drives) and the core's kinematics and dynamics
// over numpy samples.
#include "robot.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <string>
#include <utility>

#include "bindings.hpp"
#include "tpf/dynamics/coriolis.hpp"
#include "tpf/dynamics/forward_dynamics.hpp"
#include "tpf/dynamics/mass_matrix.hpp"
#include "tpf/dynamics/regressor.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/kinematics/point_jacobian.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::python {

namespace {

using VectorMap = Eigen::Map<Eigen::VectorXd>;
using RowMap = Eigen::Map<RowMatrix>;

using Argument = std::pair<const char*, py::handle>;

/// Calls f(out) for every sample after copying the arguments' sample into robot.a, .b, .c (as
/// many as given); out is the sample's storage in the result (`out` when given), `shape` per
/// sample. One sample of numpy's own float64 is read in place with nothing allocated but the
/// result (nothing at all with `out`): what a control loop calling it once per cycle pays.
template <typename F>
py::object over_samples(Robot& robot, std::initializer_list<Argument> args, const Shape& shape,
                        py::handle out, F f) {
  const int n = robot.n();
  Eigen::VectorXd* into[] = {&robot.a, &robot.b, &robot.c};
  const double* exact[3] = {};
  int k = 0;
  for (const auto& arg : args)
    exact[k++] = exact_array(arg.second, {n});
  if (std::all_of(exact, exact + k, [](const double* p) { return p != nullptr; })) {
    for (int i = 0; i < k; ++i)
      *into[i] = Eigen::Map<const Eigen::VectorXd>(exact[i], n);
    double* data = nullptr;
    py::object result = output_array(out, shape, data);
    f(data);
    return result;
  }
  InArray converted[3];
  std::pair<const char*, const InArray*> checked[3];
  k = 0;
  for (const auto& [name, h] : args) {
    converted[k] = input_array(name, h);
    checked[k] = {name, &converted[k]};
    ++k;
  }
  const Samples samples = joint_samples(n, checked, k);
  double* data = nullptr;
  py::object result =
      output_array(out, samples.stacked ? shape.stacked(samples.count) : shape, data);
  for (py::ssize_t s = 0; s < samples.count; ++s) {
    for (int i = 0; i < k; ++i)
      *into[i] = sample(converted[i], s, n);
    f(data + s * shape.size());
  }
  return result;
}

/// Homogeneous 4×4 matrix of a transform, row-major into `out`.
void write_pose(const Transform<double>& T, double* out) {
  RowMap M(out, 4, 4);
  M.setIdentity();
  M.topLeftCorner<3, 3>() = T.R;
  M.topRightCorner<3, 1>() = T.p;
}

void require_link(const Robot& robot, int link) {
  if (link < 1 || link > robot.n())
    throw py::value_error("link " + std::to_string(link) + " outside 1.." +
                          std::to_string(robot.n()));
}

void bind_properties(py::class_<Robot>& c) {
  c.def_property_readonly("name", [](const Robot& r) { return r.model.name; })
      .def_property_readonly("joint_count", &Robot::n)
      .def_property_readonly("joint_names", [](const Robot& r) { return r.model.joint_names; })
      .def_property_readonly("link_names", [](const Robot& r) { return r.model.link_names; });
  // Per-joint vectors: read-only views of the model's own.
  const auto vector = [&c](const char* name, Eigen::VectorXd Model<double, Eigen::Dynamic>::*member,
                           const char* doc) {
    c.def_property_readonly(
        name,
        [member](py::object self) {
          return readonly_view(self.cast<const Robot&>().model.*member, self);
        },
        doc);
  };
  vector("lower", &Model<double, Eigen::Dynamic>::lower, "lower position limits [rad]");
  vector("upper", &Model<double, Eigen::Dynamic>::upper, "upper position limits [rad]");
  vector("velocity_limit", &Model<double, Eigen::Dynamic>::velocity_limit, "[rad/s]");
  vector("effort_limit", &Model<double, Eigen::Dynamic>::effort_limit, "[N·m]");
  vector("gear_ratio", &Model<double, Eigen::Dynamic>::gear_ratio, "gear ratio");
  vector("torque_constant", &Model<double, Eigen::Dynamic>::torque_constant,
         "K_t, output side [N·m/A]");
  vector("current_limit", &Model<double, Eigen::Dynamic>::current_limit, "[mA]");
  vector("armature", &Model<double, Eigen::Dynamic>::armature, "reflected rotor inertia [kg·m²]");
  c.def_property_readonly(
      "mass",
      [](const Robot& r) {
        Eigen::VectorXd m(r.n() + 1);
        for (int k = 0; k <= r.n(); ++k)
          m[k] = r.model.inertias[k].mass;
        return m;
      },
      "link masses (n+1,) [kg], [0] the base");
  c.def_property_readonly(
      "com",
      [](const Robot& r) {
        RowMatrix c(r.n() + 1, 3);
        for (int k = 0; k <= r.n(); ++k)
          c.row(k) = r.model.inertias[k].com.transpose();
        return c;
      },
      "link centres of mass (n+1, 3) in the link frames [m]");
  c.def_property_readonly(
      "inertia",
      [](const Robot& r) {
        OutArray out({py::ssize_t(r.n() + 1), py::ssize_t(3), py::ssize_t(3)});
        for (int k = 0; k <= r.n(); ++k)
          RowMap(out.mutable_data() + 9 * k, 3, 3) = r.model.inertias[k].rotational;
        return out;
      },
      "link rotational inertias about their centres of mass (n+1, 3, 3), link frames [kg·m²]");
  c.def_property_readonly(
      "gravity", [](const Robot& r) { return Eigen::Vector3d(r.model.gravity); },
      "gravity in the world frame [m/s²]");
}

const char* const kOutDoc =
    " out: an array of the result's shape (float64, C-ordered) to write it into, returned.";

void bind_kinematics(py::class_<Robot>& c) {
  c.def(
      "forward_kinematics",
      [](Robot& r, py::handle q, py::handle out) {
        const int n = r.n();
        return over_samples(r, {{"q", q}}, {n + 1, 4, 4}, out, [&r, n](double* pose) {
          forward_kinematics(r.model, r.data, r.a);
          for (int k = 0; k <= n; ++k)
            write_pose(r.data.oMi[k], pose + 16 * k);
        });
      },
      py::arg("q"), py::arg("out") = py::none(),
      (std::string("World poses of links 0..n (0: base) as 4×4 homogeneous matrices: (n+1, 4, "
                   "4), or (S, n+1, 4, 4) for q of shape (S, n).") +
       kOutDoc)
          .c_str());
  c.def(
      "point_jacobian",
      [](Robot& r, py::handle q, int link, const InArray& point, py::handle out) {
        require_link(r, link);
        const Samples points = joint_samples(3, {{"point", &point}});
        const InArray qs = input_array("q", q);
        const Samples samples = joint_samples(r.n(), {{"q", &qs}});
        if (points.stacked != samples.stacked || points.count != samples.count)
          throw py::value_error("point must be (3,) for q (n,), (S, 3) for q (S, n)");
        py::ssize_t s = 0;
        return over_samples(r, {{"q", qs}}, {6, r.n()}, out, [&](double* J) {
          forward_kinematics(r.model, r.data, r.a, link);
          RowMap(J, 6, r.n()) = point_jacobian(r.model, r.data, link, sample(point, s++, 3));
        });
      },
      py::arg("q"), py::arg("link"), py::arg("point"), py::arg("out") = py::none(),
      (std::string("Jacobian (6, n), rows [linear; angular], world frame, of the point `point` "
                   "(3,) (world coordinates) fixed to link `link` (1..n); (S, 6, n) for q (S, n) "
                   "and points (S, 3).") +
       kOutDoc)
          .c_str());
}

void bind_dynamics(py::class_<Robot>& c) {
  c.def(
      "rnea",
      [](Robot& r, py::handle q, py::handle dq, py::handle ddq, py::handle out) {
        return over_samples(
            r, {{"q", q}, {"dq", dq}, {"ddq", ddq}}, {r.n()}, out,
            [&r](double* tau) { VectorMap(tau, r.n()) = rnea(r.model, r.data, r.a, r.b, r.c); });
      },
      py::arg("q"), py::arg("dq"), py::arg("ddq"), py::arg("out") = py::none(),
      (std::string("Inverse dynamics τ = M(q)q̈ + C(q,q̇)q̇ + G(q) [N·m], armature included.") +
       kOutDoc)
          .c_str());
  c.def(
      "compute_gravity",
      [](Robot& r, py::handle q, py::handle out) {
        return over_samples(r, {{"q", q}}, {r.n()}, out, [&r](double* g) {
          VectorMap(g, r.n()) = compute_gravity(r.model, r.data, r.a);
        });
      },
      py::arg("q"), py::arg("out") = py::none(),
      (std::string("Gravity torque G(q) [N·m].") + kOutDoc).c_str());
  c.def(
      "compute_mass_matrix",
      [](Robot& r, py::handle q, py::handle out) {
        return over_samples(r, {{"q", q}}, {r.n(), r.n()}, out, [&r](double* M) {
          RowMap(M, r.n(), r.n()) = compute_mass_matrix(r.model, r.data, r.a);
        });
      },
      py::arg("q"), py::arg("out") = py::none(),
      (std::string("Joint-space inertia M(q) [kg·m²], armature included.") + kOutDoc).c_str());
  c.def(
      "compute_coriolis_matrix",
      [](Robot& r, py::handle q, py::handle dq, py::handle out) {
        return over_samples(r, {{"q", q}, {"dq", dq}}, {r.n(), r.n()}, out, [&r](double* C) {
          RowMap(C, r.n(), r.n()) = compute_coriolis_matrix(r.model, r.data, r.a, r.b);
        });
      },
      py::arg("q"), py::arg("dq"), py::arg("out") = py::none(),
      (std::string("Coriolis matrix C(q, q̇) with C + Cᵀ = Ṁ.") + kOutDoc).c_str());
  c.def(
      "forward_dynamics",
      [](Robot& r, py::handle q, py::handle dq, py::handle tau, py::handle out) {
        return over_samples(
            r, {{"q", q}, {"dq", dq}, {"tau", tau}}, {r.n()}, out, [&r](double* ddq) {
              VectorMap(ddq, r.n()) = forward_dynamics(r.model, r.data, r.a, r.b, r.c);
            });
      },
      py::arg("q"), py::arg("dq"), py::arg("tau"), py::arg("out") = py::none(),
      (std::string("Joint accelerations q̈ [rad/s²] under τ.") + kOutDoc).c_str());
  c.def(
      "compute_regressor",
      [](Robot& r, py::handle q, py::handle dq, py::handle ddq, py::handle out) {
        const int n = r.n();
        Eigen::MatrixXd Y;
        return over_samples(r, {{"q", q}, {"dq", dq}, {"ddq", ddq}}, {n, 13 * n}, out,
                            [&](double* y) {
                              compute_regressor(r.model, r.data, r.a, r.b, r.c, Y);
                              RowMap(y, n, 13 * n) = Y;
                            });
      },
      py::arg("q"), py::arg("dq"), py::arg("ddq"), py::arg("out") = py::none(),
      (std::string("Regressor Y (n, 13n): τ = Y·π with π per link [m, mx, my, mz, Ixx, Ixy, "
                   "Ixz, Iyy, Iyz, Izz, armature, Coulomb, viscous].") +
       kOutDoc)
          .c_str());
}

}  // namespace

void bind_robot(py::module_& m) {
  py::class_<Robot> c(m, "Robot",
                      "A robot file's model at its joint count. Joint-space arguments are one "
                      "sample (n,) or S samples (S, n); results follow.");
  c.def(py::init([](const std::string& path) {
          return Robot(load_robot<double, Eigen::Dynamic>(path));
        }),
        py::arg("path"), "Loads a robot file (e.g. data/arm4.robot.json).");
  bind_properties(c);
  bind_kinematics(c);
  bind_dynamics(c);
  c.def("__repr__", [](const Robot& r) {
    return "tpf.Robot('" + r.model.name + "', " + std::to_string(r.n()) + " joints)";
  });
}

}  // namespace tpf::python
