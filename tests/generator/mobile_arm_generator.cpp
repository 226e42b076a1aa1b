#include "mobile_arm_generator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <random>
#include <string>

namespace tpf::test {

MobileVector mobile_arm_armature() {
  const double screw = 2 * M_PI * 10 / 0.005;  // rad per metre of travel
  MobileVector a = MobileVector::Constant(1e-5 * 100.0 * 100.0);
  a[0] = 2e-6 * screw * screw;
  return a;
}

MobileArmDynamics::MobileArmDynamics()
    : tree_(mobile_arm_tree()), armature_(mobile_arm_armature()) {
  const std::vector<std::string> chain = mobile_arm_chain_joints();
  const auto index_of = [&](const std::string& link) {
    for (std::size_t i = 0; i < tree_.size(); ++i)
      if (tree_[i].name == link) return static_cast<int>(i);
    return -1;
  };
  const auto vector = [](const std::array<double, 3>& v) {
    return Vector3<double>(v[0], v[1], v[2]);
  };
  chain_link_.assign(chain.size(), -1);
  for (const TreeLink& l : tree_) {
    Link link;
    link.parent = index_of(l.parent);
    const auto it = std::find(chain.begin(), chain.end(), l.joint);
    if (it != chain.end()) {
      link.joint = static_cast<int>(it - chain.begin());
      chain_link_[static_cast<std::size_t>(link.joint)] = static_cast<int>(links_.size());
    }
    link.prismatic = l.type == "prismatic";
    link.revolute = l.type == "revolute" || l.type == "continuous";
    link.origin_R = rpy_rotation(l.rpy);
    link.origin_p = vector(l.xyz);
    link.axis = vector(l.axis).normalized();
    link.com = vector(l.com);
    link.com_R = rpy_rotation(l.com_rpy);
    link.inertia << l.inertia[0], l.inertia[3], l.inertia[4], l.inertia[3], l.inertia[1],
        l.inertia[5], l.inertia[4], l.inertia[5], l.inertia[2];
    link.mass = l.mass;
    links_.push_back(link);
  }
  for (std::size_t i = 0; i < tree_.size(); ++i)
    for (std::size_t j = 0; j < chain.size(); ++j)
      if (at_or_below(tree_, tree_[i].name, tree_[static_cast<std::size_t>(chain_link_[j])].name))
        links_[i].movers.push_back(static_cast<int>(j));
}

std::vector<MobileArmDynamics::LinkPose> MobileArmDynamics::pose(const MobileVector& q) const {
  std::vector<LinkPose> p(links_.size());
  for (std::size_t i = 0; i < links_.size(); ++i) {  // parents come before their children
    const Link& l = links_[i];
    if (l.parent < 0) continue;  // the root: the world frame
    const Transform<double>& parent = p[static_cast<std::size_t>(l.parent)].frame;
    LinkPose& here = p[i];
    here.frame = {parent.R * l.origin_R, parent.apply(l.origin_p)};
    here.joint_origin = here.frame.p;
    here.joint_axis = here.frame.R * l.axis;
    const double position = l.joint >= 0 ? q[l.joint] : 0.0;  // the others held at zero
    if (l.prismatic)
      here.frame.p += position * here.joint_axis;
    else if (l.revolute)
      here.frame.R = here.frame.R * Eigen::AngleAxisd(position, l.axis).toRotationMatrix();
  }
  return p;
}

std::vector<MobileArmDynamics::LinkFrame> MobileArmDynamics::link_frames(
    const MobileVector& q) const {
  const std::vector<LinkPose> p = pose(q);
  std::vector<LinkFrame> frames;
  for (std::size_t i = 0; i < links_.size(); ++i)
    frames.push_back({p[i].frame.apply(links_[i].com), p[i].frame.R * links_[i].com_R});
  return frames;
}

void MobileArmDynamics::mass_and_gravity(const MobileVector& q, MobileMatrix* M,
                                         MobileVector* G) const {
  const std::vector<LinkPose> p = pose(q);
  if (M) *M = armature_.asDiagonal();
  if (G) G->setZero();
  for (std::size_t i = 0; i < links_.size(); ++i) {
    const Link& l = links_[i];
    if (l.movers.empty()) continue;  // the base and what is fixed to it
    const Vector3<double> c = p[i].frame.apply(l.com);
    Eigen::Matrix<double, 3, kMobileJoints> Jv = Eigen::Matrix<double, 3, kMobileJoints>::Zero();
    Eigen::Matrix<double, 3, kMobileJoints> Jw = Jv;
    for (const int j : l.movers) {
      const LinkPose& joint = p[static_cast<std::size_t>(chain_link_[static_cast<std::size_t>(j)])];
      if (links_[static_cast<std::size_t>(chain_link_[static_cast<std::size_t>(j)])].prismatic) {
        Jv.col(j) = joint.joint_axis;
      } else {
        Jv.col(j) = joint.joint_axis.cross(c - joint.joint_origin);
        Jw.col(j) = joint.joint_axis;
      }
    }
    if (G) *G -= Jv.transpose() * (l.mass * gravity_);
    if (!M) continue;
    const Matrix3<double> R = p[i].frame.R * l.com_R;
    const Matrix3<double> I = R * l.inertia * R.transpose();
    M->noalias() += l.mass * Jv.transpose() * Jv;
    M->noalias() += Jw.transpose() * I * Jw;
  }
}

MobileMatrix MobileArmDynamics::mass_matrix(const MobileVector& q) const {
  MobileMatrix M;
  mass_and_gravity(q, &M, nullptr);
  return M;
}

MobileVector MobileArmDynamics::gravity(const MobileVector& q) const {
  MobileVector G;
  mass_and_gravity(q, nullptr, &G);
  return G;
}

double MobileArmDynamics::potential_energy(const MobileVector& q) const {
  const std::vector<LinkFrame> frames = link_frames(q);
  double V = 0;
  for (std::size_t i = 0; i < links_.size(); ++i)
    V -= links_[i].mass * gravity_.dot(frames[i].com);
  return V;
}

MobileVector MobileArmDynamics::coriolis(const MobileVector& q, const MobileVector& dq) const {
  const double h = 1e-6;
  std::array<MobileMatrix, kMobileJoints> dM;  // dM[k] = ∂M/∂q_k
  for (int k = 0; k < kMobileJoints; ++k) {
    const MobileVector step = h * MobileVector::Unit(k);
    dM[static_cast<std::size_t>(k)] = (mass_matrix(q + step) - mass_matrix(q - step)) / (2 * h);
  }
  const auto d = [&](int k, int i, int j) { return dM[static_cast<std::size_t>(k)](i, j); };
  MobileVector c = MobileVector::Zero();
  for (int i = 0; i < kMobileJoints; ++i)
    for (int j = 0; j < kMobileJoints; ++j)
      for (int k = 0; k < kMobileJoints; ++k)
        c[i] += 0.5 * (d(k, i, j) + d(j, i, k) - d(i, j, k)) * dq[j] * dq[k];
  return c;
}

MobileVector MobileArmDynamics::rigid_effort(const MobileVector& q, const MobileVector& dq,
                                             const MobileVector& ddq) const {
  MobileMatrix M;
  MobileVector G;
  mass_and_gravity(q, &M, &G);
  return M * ddq + coriolis(q, dq) + G;
}

MobileArmMotion::MobileArmMotion(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(0.0, 0.15), angle(0.0, 2 * M_PI), middle(-0.4, 0.4);
  for (int j = 0; j < kMobileJoints; ++j) {
    const bool torso = j == 0;
    centre[j] = torso ? 0.2 : middle(rng);
    for (int h = 0; h < 3; ++h) {
      amplitude(j, h) =
          torso ? std::array{0.045, 0.022, 0.013}[static_cast<std::size_t>(h)] : 0.6 / (1.0 + h);
      frequency(j, h) = torso ? std::array{0.5, 1.1, 1.9}[static_cast<std::size_t>(h)]
                              : 0.35 + 0.13 * j + 0.9 * h + jitter(rng);
      phase(j, h) = angle(rng);
    }
  }
}

void MobileArmMotion::at(double t, MobileVector& q, MobileVector& dq, MobileVector& ddq) const {
  for (int j = 0; j < kMobileJoints; ++j) {
    q[j] = centre[j];
    dq[j] = ddq[j] = 0.0;
    for (int h = 0; h < 3; ++h) {
      const double a = amplitude(j, h), w = frequency(j, h), angle = w * t + phase(j, h);
      q[j] += a * std::sin(angle);
      dq[j] += a * w * std::cos(angle);
      ddq[j] -= a * w * w * std::sin(angle);
    }
  }
}

namespace {

std::vector<std::string> mobile_log_columns() {
  std::vector<std::string> columns = {"t"};
  for (const char* prefix : {"q", "dq", "tau"})
    for (int j = 1; j <= kMobileJoints; ++j)
      columns.push_back(offline::indexed_name(prefix, j));
  return columns;
}

double mobile_sign(double v) {
  return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0);
}

}  // namespace

offline::Log generate_mobile_arm_log(const MobileArmPlant& plant) {
  const MobileArmDynamics arm;
  const MobileArmMotion motion(plant.seed);
  std::mt19937_64 rng(plant.seed + 1000);
  std::normal_distribution<double> unit(0.0, 1.0);
  offline::Log log;
  log.source = "mobile-arm-generator-seed";
  log.source += std::to_string(plant.seed);
  log.meta.set("source", "independent test generator (tests/generator), not the twin");
  log.columns = mobile_log_columns();
  const auto n = static_cast<Eigen::Index>(plant.duration_s * plant.rate_hz);
  log.values.resize(n, 1 + 3 * kMobileJoints);
  MobileVector q, dq, ddq;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / plant.rate_hz;
    motion.at(t, q, dq, ddq);
    MobileVector effort = arm.rigid_effort(q, dq, ddq);
    for (int j = 0; j < kMobileJoints; ++j)
      effort[j] += plant.coulomb[j] * mobile_sign(dq[j]) + plant.viscous[j] * dq[j] +
                   plant.noise[j] * unit(rng);
    log.values(k, 0) = t;
    log.values.row(k).segment<kMobileJoints>(1) = q.transpose();
    log.values.row(k).segment<kMobileJoints>(1 + kMobileJoints) = dq.transpose();
    log.values.row(k).segment<kMobileJoints>(1 + 2 * kMobileJoints) = effort.transpose();
  }
  return log;
}

void write_mobile_arm_friction(const MobileArmPlant& plant, const std::filesystem::path& file) {
  std::ofstream out(file);
  out.precision(17);
  const auto array = [&](const char* key, const MobileVector& v, bool last = false) {
    out << "  \"" << key << "\": [";
    for (int j = 0; j < kMobileJoints; ++j)
      out << (j ? ", " : "") << v[j];
    out << (last ? "]\n" : "],\n");
  };
  out << "{\n  \"effort_unit\": \"N*m\",\n";
  array("coulomb", plant.coulomb);
  array("static", plant.coulomb);
  array("stribeck_velocity", MobileVector::Constant(0.05));
  array("stribeck_exponent", MobileVector::Constant(1.5));
  array("viscous", plant.viscous, true);
  out << "}\n";
}

}  // namespace tpf::test
