// Base of OutputRippleColumns and MotorRippleColumns: one ripple term of the run-time
// PositionRipple per joint, its frequency found by the residual analysis (CandidateInputs).
#pragma once

#include <limits>
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
  /// Its frequency's periods within the joint's range of motion (infinite when not given).
  static double periods_in_view(const CandidateInputs& inputs, int joint) {
    const Eigen::VectorXd& p = MotorSide ? inputs.ripple_motor_periods : inputs.ripple_periods;
    return joint >= 0 && joint < p.size() ? p[joint] : std::numeric_limits<double>::infinity();
  }
  /// Titled with its frequency (4 significant digits); judged on top of its joint's offset and
  /// spring (a short stretch of sine is one or the other). Under one period in the joint's range
  /// of motion its frequency is anything the stretch allows: it names none and cannot be told
  /// from the offset and spring (a claim of it is ambiguous with them).
  static GroupSpec group(const DesignContext& c, int joint) {
    const std::string n = joint_suffix(joint);
    const char* side = MotorSide ? "motor-angle ripple, " : "position ripple, ";
    const char* period = MotorSide ? " (%.4g periods/motor rev)" : " (%.4g periods/rev of q)";
    const std::string prefix = MotorSide ? "motor_" : "ripple_";
    const bool in_view = periods_in_view(c.inputs, joint) >= 1.0;
    GroupSpec spec{side + joint_title(joint) +
                       (in_view ? format_sentence(period, cycles(c.inputs, joint))
                                : std::string(" (under one period in the range of motion)")),
                   {prefix + "sin" + n, prefix + "cos" + n},
                   -1,
                   {"offset", "spring"}};
    spec.indistinct_from_beside = !in_view;
    return spec;
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
