// An independent log generator for an 8-joint arm with a prismatic torso, cut from a branching
// URDF (support/mobile_arm.hpp: base_link → wrist_3_link): the tree's own rigid body, every link
// of the tree its own body (the head, sensors, gripper and finger at their zero position), with
// the robot file's armature; the Coriolis term from Christoffel symbols of central differences of
// that M(q), not tpf's RNEA or regressor; Coulomb + viscous friction per joint; Gaussian effort
// noise. Writes a tpf Log in memory: t, q<j>, dq<j>, tau<j> (the torso's in m, m/s and N; the
// arm's in rad, rad/s and N·m; no ddq: the tools derive it).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "offline/log/log.hpp"
#include "support/mobile_arm.hpp"

namespace tpf::test {

inline constexpr int kMobileJoints = 8;
using MobileVector = Eigen::Matrix<double, kMobileJoints, 1>;
using MobileMatrix = Eigen::Matrix<double, kMobileJoints, kMobileJoints>;

/// The armature of write_mobile_arm's drives, rotor inertia × gear ratio²: the torso's ball screw
/// (2π·10/0.005 rad/m, 2e-6 kg·m²) reflects a mass [kg], the arm's 100:1 drives (1e-5 kg·m²) an
/// inertia [kg·m²].
MobileVector mobile_arm_armature();

/// The rigid body of the chain torso_lift … wrist_roll, evaluated on the tree of
/// mobile_arm_tree() with every link its own body (the same sums as tree_mass_matrix and
/// tree_gravity, with the link lookups done once so that a log of 10⁴ samples stays fast).
class MobileArmDynamics {
 public:
  MobileArmDynamics();

  /// A tree link's centre of mass [m] and the rotation of its inertial frame, world axes.
  struct LinkFrame {
    Vector3<double> com;
    Matrix3<double> R;
  };
  /// Every tree link at chain positions q (in mobile_arm_tree()'s order).
  std::vector<LinkFrame> link_frames(const MobileVector& q) const;
  /// M(q) of the tree plus the armature on the diagonal [kg at the torso, kg·m² at the arm].
  MobileMatrix mass_matrix(const MobileVector& q) const;
  /// G(q) = ∂V/∂q, the effort that holds the arm [N at the torso, N·m at the arm].
  MobileVector gravity(const MobileVector& q) const;
  /// V(q) = Σ m g z over the tree's links [J].
  double potential_energy(const MobileVector& q) const;
  /// C(q, q̇)q̇ with Christoffel symbols Γ_ijk = ½(∂_k M_ij + ∂_j M_ik − ∂_i M_jk) of M(q) by
  /// central differences (h = 1e-6).
  MobileVector coriolis(const MobileVector& q, const MobileVector& dq) const;
  /// M(q)q̈ + C(q, q̇)q̇ + G(q): the rigid-body effort the drives produce, armature included.
  MobileVector rigid_effort(const MobileVector& q, const MobileVector& dq,
                            const MobileVector& ddq) const;
  const std::vector<TreeLink>& tree() const { return tree_; }
  const MobileVector& armature() const { return armature_; }

 private:
  /// A tree link's constants, read once from its TreeLink.
  struct Link {
    int parent = -1;  ///< index of the parent link (−1: the root)
    int joint = -1;   ///< index of its joint in the chain (−1: fixed, or a joint held at zero)
    bool prismatic = false, revolute = false;
    Matrix3<double> origin_R, com_R, inertia;  ///< joint origin, inertial frame, inertia in it
    Vector3<double> origin_p, axis, com;
    double mass = 0;
    std::vector<int> movers;  ///< the chain joints that move it (its own and those above it)
  };
  /// A link's world frame at some q, and its joint's world origin and axis.
  struct LinkPose {
    Transform<double> frame;
    Vector3<double> joint_origin, joint_axis;
  };
  std::vector<LinkPose> pose(const MobileVector& q) const;
  void mass_and_gravity(const MobileVector& q, MobileMatrix* M, MobileVector* G) const;

  std::vector<TreeLink> tree_;
  std::vector<Link> links_;
  std::vector<int> chain_link_;  ///< per chain joint, the index of the link it moves
  MobileVector armature_;
  Vector3<double> gravity_{0.0, 0.0, -9.81};
};

/// Smooth excitation within the joint limits: joint j at centre_j + Σ_h a_jh·sin(w_jh t + φ_jh)
/// (three sines of its own frequencies, seeded phases); the torso about 0.2 m with ±8 cm of
/// travel at up to 0.075 m/s, the arm joints within ±1.5 rad.
struct MobileArmMotion {
  explicit MobileArmMotion(std::uint64_t seed);
  void at(double t, MobileVector& q, MobileVector& dq, MobileVector& ddq) const;

  MobileVector centre;
  Eigen::Matrix<double, kMobileJoints, 3> amplitude, frequency, phase;
};

/// What the generator logs.
struct MobileArmPlant {
  std::uint64_t seed = 1;
  double duration_s = 50.0;
  double rate_hz = 200.0;
  /// Coulomb [N at the torso, N·m at the arm] and viscous [N·s/m, N·m·s/rad] friction per joint.
  MobileVector coulomb = (MobileVector() << 35.0, 1.6, 1.8, 1.0, 1.2, 0.7, 0.6, 0.4).finished();
  MobileVector viscous = (MobileVector() << 400.0, 1.2, 1.5, 0.8, 0.9, 0.5, 0.4, 0.3).finished();
  /// Effort noise std per joint [N, N·m].
  MobileVector noise = (MobileVector() << 0.8, 0.06, 0.06, 0.04, 0.04, 0.03, 0.03, 0.02).finished();
};

/// The log of `plant`: effort = rigid_effort + Coulomb·sgn(q̇) + viscous·q̇ + noise.
offline::Log generate_mobile_arm_log(const MobileArmPlant& plant);

/// Writes the plant's friction as a tpf friction file (effort_unit N*m: N and N·s/m at the
/// torso; static = Coulomb, no load terms).
void write_mobile_arm_friction(const MobileArmPlant& plant, const std::filesystem::path& file);

}  // namespace tpf::test
