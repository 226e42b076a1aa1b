// Start-up loading of friction parameter files (see include/tpf/friction/friction_file.hpp).
#include "tpf/friction/friction_file.hpp"

#include <cmath>

#include "tpf/common/error.hpp"
#include "tpf/common/joint_counts.hpp"
#include "tpf/common/json_object.hpp"

namespace tpf {
namespace {

/// Opens a friction file; effort_unit and description are read here, the arrays by the callers.
json::Object open_friction_file(const std::string& path) {
  json::Object o = json::Object::read_file(path);
  o.choice("effort_unit", "N*m", {"N*m", "mA"});
  o.text("description", "");
  return o;
}

using Bound = json::Object::Bound;

// Fills `out` from the array `key`; a missing optional key leaves the default in place.
template <typename S, int N>
void read_vector(json::Object& o, const std::string& key, Bound bound, bool required,
                 JointVector<S, N>& out) {
  JointVector<double, N> v = out.template cast<double>();
  o.joint_vector<N>(key, v, required, bound);
  out = v.template cast<S>();
}

template <typename S, int N>
StribeckParameters<S, N> read_stribeck(json::Object& o) {
  StribeckParameters<S, N> p;
  read_vector<S, N>(o, "coulomb", Bound::kNonNegative, true, p.coulomb);
  read_vector<S, N>(o, "static", Bound::kNonNegative, true, p.static_friction);
  read_vector<S, N>(o, "stribeck_velocity", Bound::kPositive, true, p.stribeck_velocity);
  read_vector<S, N>(o, "stribeck_exponent", Bound::kPositive, true, p.stribeck_exponent);
  read_vector<S, N>(o, "viscous", Bound::kNonNegative, true, p.viscous);
  read_vector<S, N>(o, "load_coulomb", Bound::kNonNegative, false, p.load_coulomb);
  read_vector<S, N>(o, "load_viscous", Bound::kNonNegative, false, p.load_viscous);
  return p;
}

template <typename S, int N>
void read_bristles(json::Object& o, bool required, LuGreParameters<S, N>& p) {
  read_vector<S, N>(o, "bristle_stiffness", Bound::kPositive, required, p.bristle_stiffness);
  read_vector<S, N>(o, "bristle_damping", Bound::kNonNegative, required, p.bristle_damping);
}

}  // namespace

template <typename S, int N>
StribeckParameters<S, N> load_stribeck_parameters(const std::string& path) {
  json::Object o = open_friction_file(path);
  LuGreParameters<S, N> lugre;  // validated, not returned
  read_bristles<S, N>(o, false, lugre);
  const StribeckParameters<S, N> p = read_stribeck<S, N>(o);
  o.finish();
  return p;
}

template <typename S, int N>
LuGreParameters<S, N> load_lugre_parameters(const std::string& path) {
  json::Object o = open_friction_file(path);
  LuGreParameters<S, N> p;
  p.stribeck = read_stribeck<S, N>(o);
  read_bristles<S, N>(o, true, p);
  o.finish();
  return p;
}

std::string friction_effort_unit(const std::string& path) {
  return open_friction_file(path).choice("effort_unit", "N*m", {"N*m", "mA"});
}

#define TPF_INSTANTIATE_FRICTION_FILE(N)                                                          \
  template StribeckParameters<double, N> load_stribeck_parameters<double, N>(const std::string&); \
  template LuGreParameters<double, N> load_lugre_parameters<double, N>(const std::string&);
TPF_FOR_EACH_JOINT_COUNT(TPF_INSTANTIATE_FRICTION_FILE)
#undef TPF_INSTANTIATE_FRICTION_FILE

}  // namespace tpf
