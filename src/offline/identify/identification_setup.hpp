// What identification and diagnosis both start from: the log's joint samples checked against the
// robot file, the effort scale of the log's unit, the base parameters and the gravity load.
#pragma once

#include <memory>

#include "offline/common/run_time_types.hpp"
#include "offline/log/log.hpp"
#include "offline/samples/joint_samples.hpp"
#include "offline/samples/sample_regressors.hpp"
#include "tpf/dynamics/base_parameters.hpp"

namespace tpf::offline {

struct IdentificationSetup {
  JointSamples samples;  ///< effort in N·m
  BaseParameters base;   ///< rigid-body base parameters of the robot file's model
  /// Y of `samples`, computed once for a caller that runs identify and then diagnose on one log
  /// (prepare_diagnosis); empty: each computes the columns it reads.
  std::shared_ptr<const SampleRegressors> regressors;
  /// gravity_load of `samples`, computed once for both in the same way (prepare_diagnosis);
  /// empty: each computes it.
  std::shared_ptr<const Eigen::MatrixXd> abs_gravity;
  /// G(q) of `samples` (gravity_torque) that abs_gravity was taken from, for diagnose's log
  /// checks (prepare_diagnosis); empty: computed where needed.
  std::shared_ptr<const Eigen::MatrixXd> gravity;
};

/// extract_joint_samples(log) with the model's torque constants (the log must have the model's
/// joint count: tpf::Error naming the log otherwise), rigid_body_base_parameters(model).
IdentificationSetup prepare_identification(const Log& log, const ModelX& model,
                                           const SampleOptions& options);

/// |G_j(q_k)| [N·m] per sample k and joint j with the robot file's inertias: the load that
/// load-dependent friction scales with. NaN where the sample is invalid. Two threads.
Eigen::MatrixXd gravity_load(const ModelX& model, const JointSamples& samples);

/// The same from the samples' gravity torque G (gravity_torque): |G| at the valid samples, NaN
/// elsewhere, the same values without a second pass of G(q).
Eigen::MatrixXd gravity_load(const Eigen::MatrixXd& gravity, const JointSamples& samples);

}  // namespace tpf::offline
