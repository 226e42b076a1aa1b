#include "offline/sim/twin_arm.hpp"

#include "tpf/dynamics/energy.hpp"
#include "tpf/dynamics/forward_dynamics.hpp"
#include "tpf/dynamics/mass_matrix.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/kinematics/contact_frame.hpp"
#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/kinematics/point_jacobian.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/load_robot.hpp"
#include "tpf/skin/pad_layout.hpp"

namespace tpf::offline {

namespace {

// Adds a point mass m_p at p (link frame) to a link's inertia: new mass, centre of mass and
// rotational inertia about the new centre (parallel-axis theorem for both parts).
Inertia<double> with_point_mass(const Inertia<double>& body, double m_p, const Vector3<double>& p) {
  Inertia<double> out;
  out.mass = body.mass + m_p;
  if (out.mass <= 0) return body;
  out.com = (body.mass * body.com + m_p * p) / out.mass;
  const auto shift = [&](double m, const Vector3<double>& c) {
    const Vector3<double> d = c - out.com;
    return Matrix3<double>(m * (d.squaredNorm() * Matrix3<double>::Identity() - d * d.transpose()));
  };
  out.rotational = body.rotational + shift(body.mass, body.com) + shift(m_p, p);
  return out;
}

}  // namespace

struct TwinArm::Impl {
  Model<double, kTwinJoints> model;
  mutable Data<double, kTwinJoints> data;
  std::vector<Pad> pads;
  TwinVector current_limit_a;
};

TwinArm::TwinArm(const Scenario& scenario) : impl_(std::make_unique<Impl>()) {
  impl_->model = load_robot<double, kTwinJoints>(scenario.robot_file);
  auto& model = impl_->model;
  const auto& payload = scenario.effects.payload;
  if (payload.enabled && payload.mass > 0)
    model.inertias[kTwinJoints] =
        with_point_mass(model.inertias[kTwinJoints], payload.mass, payload.position);
  model.update_constants();
  if (!scenario.effects.gravity) model.gravity.setZero();
  impl_->pads = load_pads(scenario.pads_file, model);
  impl_->current_limit_a = model.current_limit / 1000.0;
}

TwinArm::~TwinArm() = default;
TwinArm::TwinArm(const TwinArm& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
TwinArm& TwinArm::operator=(const TwinArm& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}

TwinVector TwinArm::forward_dynamics(const TwinVector& q, const TwinVector& dq,
                                     const TwinVector& tau) const {
  return tpf::forward_dynamics(impl_->model, impl_->data, q, dq, tau);
}

TwinMatrix TwinArm::mass_matrix(const TwinVector& q) const {
  return compute_mass_matrix(impl_->model, impl_->data, q);
}

TwinVector TwinArm::gravity(const TwinVector& q) const {
  return compute_gravity(impl_->model, impl_->data, q);
}

double TwinArm::energy(const TwinVector& q, const TwinVector& dq) const {
  return kinetic_energy(impl_->model, impl_->data, q, dq) +
         potential_energy(impl_->model, impl_->data, q);
}

PadFrame TwinArm::pad_frame(const TwinVector& q, int k) const {
  const Pad& pad = impl_->pads.at(static_cast<std::size_t>(k));
  auto& data = impl_->data;
  forward_kinematics(impl_->model, data, q);
  PadFrame f;
  f.link = pad.link;
  f.centre = world_point(data, pad.link, pad.center);
  f.rotation = contact_frame_in_world(data, pad.link, pad.normal);
  f.linear_jacobian = point_jacobian(impl_->model, data, pad.link, f.centre).topRows<3>();
  return f;
}

int TwinArm::pad_count() const {
  return static_cast<int>(impl_->pads.size());
}
double TwinArm::pad_area_cm2(int k) const {
  return impl_->pads.at(k).area * 1e4;
}
const TwinVector& TwinArm::torque_constant() const {
  return impl_->model.torque_constant;
}
const TwinVector& TwinArm::current_limit() const {
  return impl_->current_limit_a;
}
const TwinVector& TwinArm::velocity_limit() const {
  return impl_->model.velocity_limit;
}
const TwinVector& TwinArm::lower() const {
  return impl_->model.lower;
}
const TwinVector& TwinArm::upper() const {
  return impl_->model.upper;
}

}  // namespace tpf::offline
