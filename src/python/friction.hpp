// Friction parameters for Python, with the vectors the samples are copied into.
#pragma once

#include <Eigen/Core>
#include <utility>

#include "arrays.hpp"
#include "tpf/friction/lugre.hpp"
#include "tpf/friction/stribeck.hpp"

namespace tpf::python {

/// Stribeck + viscous (+ load) parameters of n joints.
struct Stribeck {
  StribeckParameters<double, Eigen::Dynamic> p;
  Eigen::VectorXd dq, abs_gravity;  // samples are copied here (no allocation)

  explicit Stribeck(StribeckParameters<double, Eigen::Dynamic> parameters)
      : p(std::move(parameters)), dq(n()), abs_gravity(n()) {}
  int n() const { return static_cast<int>(p.coulomb.size()); }
};

/// stribeck_friction over samples: dq (n,) or (S, n); abs_gravity |G(q)| of the same shape, or
/// None for the load-free curve.
OutArray stribeck_torque(Stribeck& s, const InArray& dq, const py::object& abs_gravity);

/// Binds the attributes of StribeckParameters (read-only views) onto a class whose objects give
/// it by `get`.
template <typename T, typename Get>
void bind_stribeck_fields(py::class_<T>& c, Get get) {
  using P = StribeckParameters<double, Eigen::Dynamic>;
  const auto view = [&](const char* name, auto member, const char* doc) {
    c.def_property_readonly(
        name, [get, member](py::object self) { return readonly_view(get(self).*member, self); },
        doc);
  };
  view("coulomb", &P::coulomb, "τ_c [N·m]");
  view("static_friction", &P::static_friction, "τ_s, break-away [N·m]");
  view("stribeck_velocity", &P::stribeck_velocity, "q̇_s [rad/s]");
  view("stribeck_exponent", &P::stribeck_exponent, "δ");
  view("viscous", &P::viscous, "b [N·m·s/rad]");
  view("load_coulomb", &P::load_coulomb, "α_c, per unit |G|");
  view("load_viscous", &P::load_viscous, "α_v, per unit |G|·rad/s");
  view("coulomb_asymmetry", &P::coulomb_asymmetry, "a_c [N·m]");
  view("viscous_asymmetry", &P::viscous_asymmetry, "a_v [N·m·s/rad]");
  view("neighbour_load_coulomb", &P::neighbour_load_coulomb, "β (n, n)");
  view("neighbour_load_viscous", &P::neighbour_load_viscous, "γ (n, n)");
}

}  // namespace tpf::python
