#include "offline/sim/twin_arm.hpp"

#include <Eigen/Cholesky>
#include <utility>

#include "tpf/common/error.hpp"
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

/// What the twin asks of the rigid-body model; FixedArm<N> answers with tpf::core at N joints.
struct TwinArm::Impl {
  virtual ~Impl() = default;
  virtual std::unique_ptr<Impl> clone() const = 0;
  virtual TwinVector forward_dynamics(const TwinVector& q, const TwinVector& dq,
                                      const TwinVector& tau) const = 0;
  virtual TwinMatrix mass_matrix(const TwinVector& q) const = 0;
  virtual TwinVector gravity(const TwinVector& q) const = 0;
  virtual double energy(const TwinVector& q, const TwinVector& dq) const = 0;
  virtual PadFrame pad_frame(const TwinVector& q, const Pad& pad) const = 0;
  virtual Vector3<double> pad_velocity(const PadFrame& frame, const TwinVector& dq) const = 0;
  virtual TwinVector solve_spd(const TwinMatrix& a, const TwinVector& b) const = 0;

  int joints = 0;
  std::string name;
  std::vector<Pad> pads;
  TwinVector torque_constant, current_limit_a, velocity_limit, lower, upper;
};

namespace {

template <int N>
class FixedArm final : public TwinArm::Impl {
 public:
  using Vec = JointVector<double, N>;

  FixedArm(const RobotDescription& robot, const Scenario& scenario)
      : model_(make_model<double, N>(robot)) {
    const auto& payload = scenario.effects.payload;
    if (payload.enabled && payload.mass > 0)
      model_.inertias[N] = with_point_mass(model_.inertias[N], payload.mass, payload.position);
    model_.update_constants();
    if (!scenario.effects.gravity) model_.gravity.setZero();
    joints = N;
    name = model_.name;
    if (!scenario.pads_file.empty()) pads = load_pads(scenario.pads_file, model_);
    torque_constant = model_.torque_constant;
    current_limit_a = model_.current_limit / 1000.0;
    velocity_limit = model_.velocity_limit;
    lower = model_.lower;
    upper = model_.upper;
  }

  std::unique_ptr<Impl> clone() const override { return std::make_unique<FixedArm>(*this); }

  TwinVector forward_dynamics(const TwinVector& q, const TwinVector& dq,
                              const TwinVector& tau) const override {
    return tpf::forward_dynamics(model_, data_, Vec(q), Vec(dq), Vec(tau));
  }
  TwinMatrix mass_matrix(const TwinVector& q) const override {
    return compute_mass_matrix(model_, data_, Vec(q));
  }
  TwinVector gravity(const TwinVector& q) const override {
    return compute_gravity(model_, data_, Vec(q));
  }
  double energy(const TwinVector& q, const TwinVector& dq) const override {
    return kinetic_energy(model_, data_, Vec(q), Vec(dq)) + potential_energy(model_, data_, Vec(q));
  }
  PadFrame pad_frame(const TwinVector& q, const Pad& pad) const override {
    forward_kinematics(model_, data_, Vec(q));
    PadFrame f;
    f.link = pad.link;
    f.centre = world_point(data_, pad.link, pad.center);
    f.rotation = contact_frame_in_world(data_, pad.link, pad.normal);
    f.linear_jacobian = point_jacobian(model_, data_, pad.link, f.centre).template topRows<3>();
    return f;
  }
  Vector3<double> pad_velocity(const PadFrame& frame, const TwinVector& dq) const override {
    const Eigen::Matrix<double, 3, N> jacobian = frame.linear_jacobian;
    return jacobian * Vec(dq);
  }
  TwinVector solve_spd(const TwinMatrix& a, const TwinVector& b) const override {
    const Vec x = JointMatrix<double, N>(a).ldlt().solve(Vec(b));  // solved at size N, then copied
    return x;
  }

 private:
  Model<double, N> model_;
  mutable Data<double, N> data_;
};

template <int N>
std::unique_ptr<TwinArm::Impl> make_arm(const RobotDescription& robot, const Scenario& scenario) {
  if constexpr (N > kTwinMaxJoints) {
    throw Error::at(robot.source, 0, "joints",
                    "the twin simulates 1 to " + std::to_string(kTwinMaxJoints) +
                        " revolute joints; this robot has " +
                        std::to_string(robot.chain.joints.size()));
  } else {
    if (static_cast<int>(robot.chain.joints.size()) == N)
      return std::make_unique<FixedArm<N>>(robot, scenario);
    return make_arm<N + 1>(robot, scenario);
  }
}

}  // namespace

TwinArm::TwinArm(const Scenario& scenario)
    : impl_(make_arm<1>(load_robot_description(scenario.robot_file), scenario)) {}

TwinArm::~TwinArm() = default;
TwinArm::TwinArm(const TwinArm& other) : impl_(other.impl_->clone()) {}
TwinArm& TwinArm::operator=(const TwinArm& other) {
  if (this != &other) impl_ = other.impl_->clone();
  return *this;
}

TwinVector TwinArm::forward_dynamics(const TwinVector& q, const TwinVector& dq,
                                     const TwinVector& tau) const {
  return impl_->forward_dynamics(q, dq, tau);
}
TwinMatrix TwinArm::mass_matrix(const TwinVector& q) const {
  return impl_->mass_matrix(q);
}
TwinVector TwinArm::gravity(const TwinVector& q) const {
  return impl_->gravity(q);
}
double TwinArm::energy(const TwinVector& q, const TwinVector& dq) const {
  return impl_->energy(q, dq);
}
PadFrame TwinArm::pad_frame(const TwinVector& q, int k) const {
  return impl_->pad_frame(q, impl_->pads.at(static_cast<std::size_t>(k)));
}
Vector3<double> TwinArm::pad_velocity(const PadFrame& frame, const TwinVector& dq) const {
  return impl_->pad_velocity(frame, dq);
}
TwinVector TwinArm::solve_spd(const TwinMatrix& a, const TwinVector& b) const {
  return impl_->solve_spd(a, b);
}

int TwinArm::pad_count() const {
  return static_cast<int>(impl_->pads.size());
}
int TwinArm::joints() const {
  return impl_->joints;
}
const std::string& TwinArm::name() const {
  return impl_->name;
}
double TwinArm::pad_area_cm2(int k) const {
  return impl_->pads.at(static_cast<std::size_t>(k)).area * 1e4;
}
const TwinVector& TwinArm::torque_constant() const {
  return impl_->torque_constant;
}
const TwinVector& TwinArm::current_limit() const {
  return impl_->current_limit_a;
}
const TwinVector& TwinArm::velocity_limit() const {
  return impl_->velocity_limit;
}
const TwinVector& TwinArm::lower() const {
  return impl_->lower;
}
const TwinVector& TwinArm::upper() const {
  return impl_->upper;
}

}  // namespace tpf::offline
