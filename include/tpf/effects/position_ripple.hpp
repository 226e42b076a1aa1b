// Position-periodic torque ripple (gear meshing, cogging): an added effect made of terms
//   τ_j += a_sin·sin(n·θ) + a_cos·cos(n·θ),  θ = q_j (output side) or G_j·q_j (motor side).
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "tpf/effects/effect_input.hpp"

namespace tpf {

/// One ripple term of joint j.
template <typename S>
struct RippleTerm {
  int joint = 0;            ///< 0-based joint index
  S cycles_per_rev = S(0);  ///< n, periods per revolution of θ
  bool motor_side = false;  ///< θ = gear_ratio·q (motor angle) instead of q
  S sin_amplitude = S(0);   ///< [N·m]
  S cos_amplitude = S(0);   ///< [N·m]
};

template <typename S, int N>
struct PositionRipple {
  static constexpr std::string_view key = "ripple";  ///< diagnose's name (output side)
  static constexpr int kColumns = 2;                 ///< basis functions per term
  static constexpr int kMaxTerms = 16;

  int count = 0;  ///< terms in use
  std::array<RippleTerm<S>, kMaxTerms> terms{};
  int joints = N == Eigen::Dynamic ? 0 : N;  ///< the arm's joint count (a term's joint is below)

  /// Sets the joint count to n, with no terms.
  void resize(int n) {
    joints = n;
    count = 0;
  }
  /// The same effect of another joint-count type.
  template <int From>
  void assign(const PositionRipple<S, From>& from) {
    count = from.count;
    terms = from.terms;
    joints = from.joints;
  }
  int columns() const noexcept { return kColumns; }

  /// The phase n·θ of `term`: n·q_j, or n·G_j·q_j on the motor side.
  static S phase(const EffectInput<S, N>& x, const RippleTerm<S>& term) noexcept {
    const int j = term.joint;
    return term.motor_side ? term.cycles_per_rev * x.gear_ratio[j] * x.q[j]
                           : term.cycles_per_rev * x.q[j];
  }
  /// φ = sin(n·θ), cos(n·θ): the columns of `term`'s joint (its amplitudes are the coefficients).
  static void basis(const EffectInput<S, N>& x, const RippleTerm<S>& term, S* columns) noexcept {
    using std::cos, std::sin;
    const S a = phase(x, term);
    columns[0] = sin(a);
    columns[1] = cos(a);
  }
  /// Appends a term (ignored when all kMaxTerms are in use; a parameter file holds at most that).
  void add(const RippleTerm<S>& term) noexcept {
    if (count < kMaxTerms) terms[count++] = term;
  }
  /// Sets the amplitudes of joint `joint`'s terms on one side to zero.
  void clear(int joint, bool motor_side) noexcept {
    for (int i = 0; i < count; ++i)
      if (terms[i].joint == joint && terms[i].motor_side == motor_side)
        terms[i].sin_amplitude = terms[i].cos_amplitude = S(0);
  }
  bool present() const noexcept { return count > 0; }
  void add_torque(const EffectInput<S, N>& x, JointVector<S, N>& tau) const noexcept {
    S phi[kColumns];
    for (int i = 0; i < count; ++i) {
      basis(x, terms[i], phi);
      tau[terms[i].joint] += phi[0] * terms[i].sin_amplitude + phi[1] * terms[i].cos_amplitude;
    }
  }

  /// Parameter file, "added_effects": "ripple": [{"joint": 1-based, "cycles_per_rev": n > 0,
  /// "motor_side": bool (false), "sin": a_sin, "cos": a_cos}, …] (optional, ≤ kMaxTerms).
  template <typename Fields>
  void read(Fields& added) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    auto items = added.children("ripple");
    if (items.size() > static_cast<std::size_t>(kMaxTerms))
      added.fail("ripple", "must be an array of at most " + std::to_string(kMaxTerms) + " terms");
    count = 0;
    for (auto& r : items) {
      RippleTerm<S> t;
      t.joint = r.integer("joint", 1, joints) - 1;
      t.cycles_per_rev = r.number("cycles_per_rev", 1e-9, kInf);
      t.motor_side = r.boolean("motor_side", t.motor_side);
      t.sin_amplitude = r.number("sin", -kInf, kInf);
      t.cos_amplitude = r.number("cos", -kInf, kInf);
      r.finish();
      add(t);
    }
  }
  template <typename Json>
  void write(Json& added) const {
    Json items = Json::array();
    for (int i = 0; i < count; ++i)
      items.push_back({{"joint", terms[i].joint + 1},
                       {"cycles_per_rev", terms[i].cycles_per_rev},
                       {"motor_side", terms[i].motor_side},
                       {"sin", terms[i].sin_amplitude},
                       {"cos", terms[i].cos_amplitude}});
    added["ripple"] = items;
  }
};

}  // namespace tpf
