#include "offline/sim/twin_arm.hpp"

#include "tpf/common/error.hpp"
#include "tpf/dynamics/energy.hpp"
#include "tpf/dynamics/mass_matrix.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/kinematics/contact_frame.hpp"
#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/kinematics/point_jacobian.hpp"
#include "tpf/model/load_robot.hpp"

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

TwinArm::TwinArm(const Scenario& scenario) {
  const RobotDescription robot = load_robot_description(scenario.robot_file);
  if (robot.chain.joints.empty())
    throw Error::at(robot.source, 0, "joints",
                    "the twin simulates arms of 1 or more joints; this "
                    "robot has none");
  model_ = make_model<double, Eigen::Dynamic>(robot);
  const int n = model_.joint_count();
  const auto& payload = scenario.effects.payload;
  if (payload.enabled && payload.mass > 0)
    model_.inertias[n] = with_point_mass(model_.inertias[n], payload.mass, payload.position);
  model_.update_constants();
  if (!scenario.effects.gravity) model_.gravity.setZero();
  data_ = Data<double, Eigen::Dynamic>(model_);
  zero_ = TwinVector::Zero(n);
  jacobian_.setZero(6, n);
  if (!scenario.pads_file.empty()) pads_ = load_pads(scenario.pads_file, model_);
  current_limit_a_ = model_.current_limit / 1000.0;
}

TwinVector TwinArm::forward_dynamics(const TwinVector& q, const TwinVector& dq,
                                     const TwinVector& tau) const {
  TwinVector ddq(model_.joint_count());
  forward_dynamics(q, dq, tau, ddq);
  return ddq;
}
void TwinArm::forward_dynamics(const TwinVector& q, const TwinVector& dq, const TwinVector& tau,
                               TwinVector& ddq) const {
  // tpf::forward_dynamics's steps, with the twin's Cholesky solve.
  compute_mass_matrix(model_, data_, q);
  detail::newton_euler_passes(model_, data_, dq, zero_, Vector3<double>(-model_.gravity));
  mass_factor_.compute(data_.M);
  ddq = tau - data_.tau;
  mass_factor_.solve_in_place(ddq);
}
const TwinMatrix& TwinArm::mass_matrix(const TwinVector& q) const {
  return compute_mass_matrix(model_, data_, q);
}
const TwinVector& TwinArm::gravity(const TwinVector& q) const {
  return compute_gravity(model_, data_, q);
}
double TwinArm::energy(const TwinVector& q, const TwinVector& dq) const {
  return kinetic_energy(model_, data_, q, dq) + potential_energy(model_, data_, q);
}
PadFrame TwinArm::pad_frame(const TwinVector& q, int k) const {
  PadFrame f;
  pad_frame(q, k, f);
  return f;
}
void TwinArm::pad_frame(const TwinVector& q, int k, PadFrame& f) const {
  const Pad& pad = pads_.at(static_cast<std::size_t>(k));
  forward_kinematics(model_, data_, q);
  f.link = pad.link;
  f.centre = world_point(data_, pad.link, pad.center);
  f.rotation = contact_frame_in_world(data_, pad.link, pad.normal);
  point_jacobian(model_, data_, pad.link, f.centre, jacobian_);
  f.linear_jacobian = jacobian_.topRows<3>();
}
Vector3<double> TwinArm::pad_velocity(const PadFrame& frame, const TwinVector& dq) const {
  return multiply(frame.linear_jacobian, dq);
}

int TwinArm::pad_count() const {
  return static_cast<int>(pads_.size());
}
int TwinArm::joints() const {
  return model_.joint_count();
}
const std::string& TwinArm::name() const {
  return model_.name;
}
double TwinArm::pad_area_cm2(int k) const {
  return pads_.at(static_cast<std::size_t>(k)).area * 1e4;
}
const TwinVector& TwinArm::torque_constant() const {
  return model_.torque_constant;
}
const TwinVector& TwinArm::current_limit() const {
  return current_limit_a_;
}
const TwinVector& TwinArm::velocity_limit() const {
  return model_.velocity_limit;
}
const TwinVector& TwinArm::lower() const {
  return model_.lower;
}
const TwinVector& TwinArm::upper() const {
  return model_.upper;
}
const TwinMatrix& TwinArm::coupling() const {
  return model_.coupling;
}
bool TwinArm::coupled() const {
  return model_.coupled;
}

}  // namespace tpf::offline
