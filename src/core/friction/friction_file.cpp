// Start-up loading of friction parameter files (see include/tpf/friction/friction_file.hpp).
#include "tpf/friction/friction_file.hpp"

#include "core/common/json_object.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf {
namespace {

using Stribeck = StribeckParameters<double, Eigen::Dynamic>;
using LuGre = LuGreParameters<double, Eigen::Dynamic>;
using Bound = json::Object::Bound;

/// Opens a friction file; effort_unit and description are read here, the arrays by the callers.
json::Object open_friction_file(const std::string& path) {
  json::Object o = json::Object::read_file(path);
  o.choice("effort_unit", "N*m", {"N*m", "mA"});
  o.text("description", "");
  return o;
}

/// The joint count: `joints` when given, else the length of the first array, "coulomb".
int joint_count(json::Object& o, int joints) {
  return joints > 0 ? joints : o.joint_count_of("coulomb");
}

Stribeck read_stribeck(json::Object& o, int n) {
  Stribeck p;
  p.resize(n);
  o.joint_vector("coulomb", p.coulomb, true, Bound::kNonNegative);
  o.joint_vector("static", p.static_friction, true, Bound::kNonNegative);
  o.joint_vector("stribeck_velocity", p.stribeck_velocity, true, Bound::kPositive);
  o.joint_vector("stribeck_exponent", p.stribeck_exponent, true, Bound::kPositive);
  o.joint_vector("viscous", p.viscous, true, Bound::kNonNegative);
  o.joint_vector("load_coulomb", p.load_coulomb, false, Bound::kNonNegative);
  o.joint_vector("load_viscous", p.load_viscous, false, Bound::kNonNegative);
  return p;
}

/// Reads the bristle parameters into `p` (sized for the joints already).
void read_bristles(json::Object& o, bool required, LuGre& p) {
  o.joint_vector("bristle_stiffness", p.bristle_stiffness, required, Bound::kPositive);
  o.joint_vector("bristle_damping", p.bristle_damping, required, Bound::kNonNegative);
}

}  // namespace

Stribeck load_stribeck_parameters(const std::string& path, int joints) {
  json::Object o = open_friction_file(path);
  const int n = joint_count(o, joints);
  LuGre lugre;  // validated, not returned
  lugre.resize(n);
  read_bristles(o, false, lugre);
  const Stribeck p = read_stribeck(o, n);
  o.finish();
  return p;
}

LuGre load_lugre_parameters(const std::string& path, int joints) {
  json::Object o = open_friction_file(path);
  const int n = joint_count(o, joints);
  LuGre p;
  p.resize(n);
  p.stribeck = read_stribeck(o, n);
  read_bristles(o, true, p);
  o.finish();
  return p;
}

std::string friction_effort_unit(const std::string& path) {
  return open_friction_file(path).choice("effort_unit", "N*m", {"N*m", "mA"});
}

}  // namespace tpf

TPF_UNOPTIMISED_WHEN_SANITIZED_END
