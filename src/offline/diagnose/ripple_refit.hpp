// Pass 3 of diagnose, before the selection: the frequency of an output ripple with few periods in
// its joint's range, fitted again on the residual of the declared model refitted beside it. Over
// a few periods, the declared fit (rigid body, friction) absorbs part of the ripple and shifts the
// frequency the declared residual shows (on the measured Kinova logs with 2 periods planted in
// joint 5's range: 3.886/rev for 3.453); beside the ripple's columns it cannot.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "offline/fit/gram_fit.hpp"
#include "offline/identify/effect_design.hpp"

namespace tpf::offline {

/// Output ripples with this many periods in view or fewer are fitted again (from 1: under one
/// period the frequency is not named).
inline constexpr double kFewRipplePeriods = 4.0;

/// The joints' output-ripple frequencies and periods in view.
struct RippleFrequencies {
  Eigen::VectorXd cycles, periods;
};

/// For each joint whose output ripple (design.candidates()) has 1 to kFewRipplePeriods periods in
/// view: the declared columns and the ripple's fitted on `selection`'s rows of `grams`, and the
/// frequency fitted again (joint_output_ripple) on effort − the declared part of that fit. Other
/// joints keep theirs. One pass over the samples when any joint qualifies, none otherwise.
RippleFrequencies refitted_ripple_frequencies(const EffectDesign& design, const DesignGrams& grams,
                                              const JointSamples& samples,
                                              const std::vector<int>& declared_columns,
                                              const FitSelection& selection);

}  // namespace tpf::offline
