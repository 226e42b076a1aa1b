// The estimator of any arm, built at start-up from the files the offline tools write: a
// controller names the arm's joint count, pad count and compensator as types and loads the rest,
//   auto est = tpf::load_estimator<7, 0, tpf::PerJointTcn<tpf::BFloat16Weights, 16>>(files);
//   const auto& out = est->update(sample);   // per cycle
// The loading is compiled once, at the run-time joint count (Eigen::Dynamic); a program of N
// joints converts its result header-only (joint_count_cast), and an offline tool names
// Eigen::Dynamic for N (and P) to run one compiled estimator for any arm.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "tpf/estimation/compensator_types.hpp"
#include "tpf/estimation/compensator_weight_files.hpp"
#include "tpf/estimation/estimator.hpp"
#include "tpf/estimation/estimator_parameters.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/skin/pad_layout.hpp"

namespace tpf {

/// The files of an estimator.
struct EstimatorFiles {
  std::string params;     ///< nominal model (tpf-params, `tpf identify` / `tpf diagnose`)
  std::string robot;      ///< robot file the parameters were identified for
  std::string pads;       ///< pad layout (tpf-pads); empty: no skin
  std::string estimator;  ///< estimator parameters (tpf-estimator, `tpf calibrate`)
  /// Compensator weights (find_compensator_weights); empty: no compensator.
  std::string weights;
};

/// Everything an N-joint estimator is built from, loaded (N = Eigen::Dynamic: any joint count,
/// the nominal model's).
template <int N>
struct EstimatorSetup {
  NominalModel<double, N> nominal;
  std::vector<Pad> pads;
  EstimatorParameters<double, N> parameters;
  CompensatorWeightFiles weights;
};

/// The same setup with the joint count as type `To`: Eigen::Dynamic, or a fixed count that must
/// equal the nominal model's (tpf::Error naming both otherwise). Start-up code.
template <int To, int From>
EstimatorSetup<To> joint_count_cast(const EstimatorSetup<From>& from) {
  EstimatorSetup<To> to;
  to.nominal = joint_count_cast<To>(from.nominal);
  to.pads = from.pads;
  to.parameters = joint_count_cast<To>(from.parameters);
  to.weights = from.weights;
  return to;
}

/// Start-up: loads every file of `files` (core loaders only) for the robot file's joint count
/// (`joints` > 0: it must be that many). Throws tpf::Error naming the file and field on bad
/// input, and when a file has another joint count than the robot's or than `joints`.
EstimatorSetup<Eigen::Dynamic> load_estimator_setup(const EstimatorFiles& files, int joints = 0);

/// load_estimator_setup for a program of N joints (header-only conversion; N = Eigen::Dynamic:
/// any count).
template <int N>
EstimatorSetup<N> load_estimator_setup(const EstimatorFiles& files) {
  return joint_count_cast<N>(load_estimator_setup(files, N == Eigen::Dynamic ? 0 : N));
}

/// The estimator of an N-joint arm with P pads (0: no skin) and the compensator `Kind`
/// (NoCompensator, PerJointTcn<NetScalar, Hidden>, AllJointsTcn<Hidden>).
template <int N, int P, typename Kind = NoCompensator, typename S = double>
using EstimatorOf = Estimator<S, N, P, typename Kind::template For<S, N>>;

/// Start-up: the estimator of `setup` on the heap, its compensator's weights loaded. Throws
/// tpf::Error when the pad layout does not have P pads or the weight files are not of `Kind`.
/// N = Eigen::Dynamic: sized for setup.nominal's joint count.
template <int N, int P, typename Kind = NoCompensator>
std::unique_ptr<EstimatorOf<N, P, Kind>> make_estimator(const EstimatorSetup<N>& setup) {
  auto e = std::make_unique<EstimatorOf<N, P, Kind>>(setup.nominal, setup.pads, setup.parameters);
  Kind::template load<double, N>(e->compensator(), setup.weights);
  e->set_compensated_joints(compensated_joints(setup.weights, e->joint_count(),
                                               setup.parameters.compensator_min_held_out_gain));
  return e;
}

/// Start-up: load_estimator_setup, then make_estimator.
template <int N, int P, typename Kind = NoCompensator>
std::unique_ptr<EstimatorOf<N, P, Kind>> load_estimator(const EstimatorFiles& files) {
  return make_estimator<N, P, Kind>(load_estimator_setup<N>(files));
}

}  // namespace tpf
