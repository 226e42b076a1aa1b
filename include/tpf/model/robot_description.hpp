// Start-up loading of a robot: the URDF chain and the drive data that URDF cannot hold.
// These functions allocate and throw tpf::Error; call them once, before the control loop.
#pragma once

#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tpf/common/error.hpp"
#include "tpf/common/types.hpp"
#include "tpf/model/inertia.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

/// One revolute or prismatic joint of a chain, with fixed joints already folded in.
struct ChainJoint {
  std::string name;
  std::string child_link;
  JointType type = JointType::revolute;  ///< a continuous joint is revolute without limits.
  Transform<double> placement;           ///< joint frame in the previous moving link's frame.
  Vector3<double> axis;                  ///< unit, joint frame.
  double lower = 0, upper = 0;           ///< [rad] or [m].
  /// [rad/s] and [N·m], or [m/s] and [N] for a prismatic joint; +∞ for a joint without <limit> (a
  /// continuous joint needs none).
  double velocity_limit = std::numeric_limits<double>::infinity();
  double effort_limit = std::numeric_limits<double>::infinity();
};

/// A chain of revolute and prismatic joints read from a URDF. Fixed joints are merged: a fixed
/// child's inertia is added to the moving link it hangs from, and fixed offsets go into the next
/// placement. Branches off the chain (cut from a tree by ChainEnds) are folded in the same way, at
/// the zero position of their own movable joints.
struct ChainDescription {
  std::string source;  ///< the file it came from, for messages.
  std::string robot_name;
  std::string base_link;  ///< the chain's root link: the model's base and world frame.
  std::string tip_link;   ///< the last link of the chain.
  std::vector<ChainJoint> joints;
  std::vector<Inertia<double>> inertias;  ///< [0] base, then one per joint's child link.
};

/// Drive data per joint (what URDF cannot hold).
struct DriveDescription {
  std::string joint;
  std::string motor;
  /// Motor radians per output radian; per metre of travel for a prismatic joint [rad/m] (a ball
  /// screw of lead ℓ after a gearbox of ratio r: r·2π/ℓ). Signed: negative where the motor turns
  /// against its joint.
  double gear_ratio = 1;
  /// Other joints this motor also turns with (joint name → coefficient c): its angle is
  /// gear_ratio·(q_own + Σ c·q_other). Empty for a motor that drives its own joint only.
  std::vector<std::pair<std::string, double>> coupled_to;
  double rotor_inertia = 0;    ///< [kg·m²] motor side.
  double torque_constant = 1;  ///< [N·m/A] output side ([N/A] for a prismatic joint).
  double current_limit = 0;    ///< [mA].
  /// The rotor reflected to the output: [kg·m²], or a mass [kg] for a prismatic joint.
  double armature() const { return rotor_inertia * gear_ratio * gear_ratio; }
};

/// A robot file (data/<robot>.robot.json): URDF chain + drives + gravity + the pad layout path.
struct RobotDescription {
  std::string source;
  ChainDescription chain;
  std::vector<DriveDescription> drives;  ///< in chain order.
  /// The transmission's coupling C (motors × joints, Model::coupling) from the drives'
  /// coupled_to: the identity where no motor is coupled; checked invertible.
  Eigen::MatrixXd coupling;
  Vector3<double> gravity{0, 0, -9.81};
  std::filesystem::path pads_file;      ///< empty if the robot has no skin.
  std::filesystem::path friction_file;  ///< the twin's true friction; empty if none is named.
};

/// Refuses a model whose motors are coupled where `what` (a tool or model part) takes each
/// drive's friction on its own joint (the dynamics, the regressor, the nominal model, identify
/// and the twin carry the coupling). Throws tpf::Error naming the robot and coupled_to.
template <typename S, int N>
void require_uncoupled_drives(const Model<S, N>& model, std::string_view what) {
  if (!model.coupled) return;
  throw Error::at(model.name + " (robot file)", 0, "coupled_to",
                  std::string(what) +
                      " takes each drive's friction on its own joint; coupled motors are "
                      "modelled by the dynamics, the nominal model and identify only");
}

/// The ends of the chain to cut from a URDF: empty names take the URDF's root link and the end of
/// the serial chain below the root.
struct ChainEnds {
  std::string root;    ///< the chain's base link (the world frame); empty: the URDF's root.
  std::string tip;     ///< the chain's last link; empty: where the serial chain below root ends.
  std::string source;  ///< the file that names them (a robot file), for messages.
};

/// Reads a URDF and extracts the chain of revolute, continuous and prismatic joints from the root
/// link to the tip link (`ends`). Without a tip the robot below the root must be serial; with one
/// the chain is the path from the root to the tip, and every link off that path (the branches of
/// a tree, and what hangs below the tip) is folded into the chain link it hangs from as fixed
/// mass, its own movable joints at their zero position. Links above the root are the base.
/// Refuses, naming the file and the joint or link: malformed XML, a branching tree without a tip,
/// a root or tip that is no link of the file or a tip not below the root, floating or planar
/// joints on the chain, a prismatic joint without a travel range, a zero axis, a negative mass or
/// an inertia that is not positive semi-definite, a body moved by a joint in which no link has an
/// <inertial> (an <inertial> with mass 0 is allowed; a link without one fixed to a link with one is
/// massless). An inertia that breaks the triangle inequality is loaded with a warning (makers'
/// files do: the Gen3's).
ChainDescription load_urdf_chain(const std::filesystem::path& urdf_file,
                                 const ChainEnds& ends = {});

/// Reads a robot file (JSON, format "tpf-robot" version 1) and the URDF it names (relative paths
/// are taken from the robot file's folder), cut at its optional "root_link" and "tip_link". Every
/// drive must name a joint of the chain, in order.
RobotDescription load_robot_description(const std::filesystem::path& robot_file);

}  // namespace tpf
