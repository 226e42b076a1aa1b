// tpf.StribeckParameters and tpf.LuGreParameters: friction files and the friction torque over
// numpy samples.
#include "friction.hpp"

#include <string>

#include "bindings.hpp"
#include "tpf/friction/friction_file.hpp"

namespace tpf::python {

namespace {

/// LuGre parameters of n joints.
struct LuGre {
  LuGreParameters<double, Eigen::Dynamic> p;
  int n() const { return static_cast<int>(p.bristle_stiffness.size()); }
};

/// LuGre friction along a sampled motion: dq (S, n) at steps of dt from deflection z0 (zeros when
/// None); returns (τ_f (S, n), the deflection after the last sample).
py::tuple lugre_simulate(const LuGre& l, const InArray& dq, double dt, const py::object& abs_g,
                         const py::object& z0) {
  const int n = l.n();
  if (!(dt > 0)) throw py::value_error("dt must be > 0, got " + std::to_string(dt));
  InArray gravity = abs_g.is_none() ? InArray({dq.ndim() == 2 ? dq.shape(0) : 1, py::ssize_t(n)})
                                    : abs_g.cast<InArray>();
  if (abs_g.is_none()) std::fill_n(gravity.mutable_data(), gravity.size(), 0.0);
  const Samples samples = joint_samples(n, {{"dq", &dq}, {"abs_gravity", &gravity}});
  LuGreState<double, Eigen::Dynamic> state{Eigen::VectorXd::Zero(n)};
  if (!z0.is_none()) {
    const InArray z = z0.cast<InArray>();
    joint_samples(n, {{"z0", &z}});
    if (z.ndim() != 1) throw py::value_error("z0 must have shape (" + std::to_string(n) + ",)");
    state.z = sample(z, 0, n);
  }
  OutArray tau = new_output(samples, {n});
  Eigen::VectorXd v(n), g(n);
  for (py::ssize_t s = 0; s < samples.count; ++s) {
    v = sample(dq, s, n);
    g = sample(gravity, s, n);
    Eigen::Map<Eigen::VectorXd>(output_sample(tau, s, n), n) = lugre_step(l.p, state, v, g, dt);
  }
  return py::make_tuple(tau, Eigen::VectorXd(state.z));
}

}  // namespace

OutArray stribeck_torque(Stribeck& s, const InArray& dq, const py::object& abs_gravity) {
  const int n = s.n();
  const bool loaded = !abs_gravity.is_none();
  const InArray gravity = loaded ? abs_gravity.cast<InArray>() : dq;
  const Samples samples = joint_samples(n, {{"dq", &dq}, {"abs_gravity", &gravity}});
  OutArray out = new_output(samples, {n});
  for (py::ssize_t i = 0; i < samples.count; ++i) {
    s.dq = sample(dq, i, n);
    Eigen::Map<Eigen::VectorXd> tau(output_sample(out, i, n), n);
    if (loaded) {
      s.abs_gravity = sample(gravity, i, n);
      tau = stribeck_friction(s.p, s.dq, s.abs_gravity);
    } else {
      tau = stribeck_friction(s.p, s.dq);
    }
  }
  return out;
}

void bind_friction(py::module_& m) {
  py::class_<Stribeck> stribeck(m, "StribeckParameters",
                                "Stribeck + viscous friction with load dependence, N·m.");
  bind_stribeck_fields(stribeck, [](py::object self) -> const StribeckParameters<double, -1>& {
    return self.cast<const Stribeck&>().p;
  });
  stribeck.def_property_readonly("joint_count", &Stribeck::n)
      .def("friction", &stribeck_torque, py::arg("dq"), py::arg("abs_gravity") = py::none(),
           "Friction torque [N·m] at velocities dq (n,) or (S, n), under load |G(q)| "
           "`abs_gravity` (same shape; None: no load). sgn(0) = 0.");
  m.def(
      "load_stribeck_parameters",
      [](const std::string& path) { return Stribeck(load_stribeck_parameters(path)); },
      py::arg("path"), "Reads a friction file (data/arm4.friction.json) in N·m.");

  py::class_<LuGre> lugre(m, "LuGreParameters", "LuGre friction: Stribeck curve plus bristles.");
  lugre.def_property_readonly("joint_count", &LuGre::n)
      .def_property_readonly("stribeck", [](const LuGre& l) { return Stribeck(l.p.stribeck); })
      .def_property_readonly(
          "bristle_stiffness",
          [](py::object self) {
            return readonly_view(self.cast<const LuGre&>().p.bristle_stiffness, self);
          },
          "σ0 [N·m/rad]")
      .def_property_readonly(
          "bristle_damping",
          [](py::object self) {
            return readonly_view(self.cast<const LuGre&>().p.bristle_damping, self);
          },
          "σ1 [N·m·s/rad]")
      .def("simulate", &lugre_simulate, py::arg("dq"), py::arg("dt"),
           py::arg("abs_gravity") = py::none(), py::arg("z0") = py::none(),
           "Friction along sampled velocities dq (S, n) at steps of dt [s] from bristle "
           "deflection z0 (zeros when None): (torque (S, n) [N·m], final deflection (n,)).");
  m.def(
      "load_lugre_parameters",
      [](const std::string& path) { return LuGre{load_lugre_parameters(path)}; }, py::arg("path"),
      "Reads a friction file with the LuGre keys (bristle_stiffness, bristle_damping).");
}

}  // namespace tpf::python
