// Base of OutputRippleColumns and MotorRippleColumns: one ripple term of the run-time
// PositionRipple per joint, its frequency found by the residual analysis (CandidateInputs).
#pragma once

#include <string>
#include <vector>

#include "offline/effects/design_context.hpp"
#include "offline/effects/feature_group.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/effects/written_model.hpp"
#include "offline/report/text_format.hpp"
#include "tpf/effects/position_ripple.hpp"

namespace tpf::offline {

template <bool MotorSide>
struct RippleColumns {
  static constexpr WrittenTo written_to = WrittenTo::kAddedEffects;
  static constexpr bool kSharedGroupFirst = false;

  /// Periods per revolution of θ found for `joint`, 0 = none.
  static double cycles(const CandidateInputs& inputs, int joint) {
    const Eigen::VectorXd& c = MotorSide ? inputs.ripple_motor_cycles : inputs.ripple_cycles;
    return joint >= 0 && joint < c.size() ? c[joint] : 0.0;
  }
  static bool offered(const DesignContext& c, int joint) {
    const Eigen::VectorXd& n = MotorSide ? c.inputs.ripple_motor_cycles : c.inputs.ripple_cycles;
    return n.size() == c.joints && cycles(c.inputs, joint) > 0;
  }
  /// Titled with its frequency; judged on top of its joint's offset and spring (a short stretch
  /// of sine is one or the other).
  static GroupSpec group(const DesignContext& c, int joint) {
    const std::string n = joint_suffix(joint);
    const char* side = MotorSide ? "motor-angle ripple, " : "position ripple, ";
    const char* period = MotorSide ? " (%g periods/motor rev)" : " (%g periods/rev of q)";
    const std::string prefix = MotorSide ? "motor_" : "ripple_";
    return {side + joint_title(joint) + format_sentence(period, cycles(c.inputs, joint)),
            {prefix + "sin" + n, prefix + "cos" + n},
            -1,
            {"offset", "spring"}};
  }

  /// The term of `joint` with the amplitudes a_sin, a_cos.
  static RippleTerm<double> term(const CandidateInputs& inputs, int joint, double a_sin = 0,
                                 double a_cos = 0) {
    return {joint, cycles(inputs, joint), MotorSide, a_sin, a_cos};
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    PositionRipple<double, Eigen::Dynamic>::basis(row.motion, term(row.inputs, joint), out);
  }
  static void write(const double* coefficients, int joint, WrittenModel& out) {
    if (coefficients[0] == 0.0 && coefficients[1] == 0.0) return;
    out.nominal.added.get<PositionRipple>().add(
        term(out.inputs, joint, coefficients[0], coefficients[1]));
  }
  static void remove(int joint, NominalModelX& nominal) {
    nominal.added.get<PositionRipple>().clear(joint, MotorSide);
  }
};

}  // namespace tpf::offline
