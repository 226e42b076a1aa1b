#include "offline/replay/replay_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tpf/estimation/proprioceptive_estimate.hpp"
#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/model/effort_unit.hpp"

namespace tpf::offline {
namespace {

/// 1.4826·MAD(x): the std of Gaussian samples, robust to outliers. NaN when x is empty.
double robust_std(std::vector<double>& x) {
  if (x.empty()) return std::nan("");
  const auto mid = x.begin() + static_cast<std::ptrdiff_t>(x.size() / 2);
  std::nth_element(x.begin(), mid, x.end());
  const double median = *mid;
  for (double& v : x)
    v = std::abs(v - median);
  std::nth_element(x.begin(), mid, x.end());
  return 1.4826 * *mid;
}

/// σ of the effort of joint j (1-based) over consecutive static rows.
double effort_noise(const Log& log, const std::string& effort, int j, double period) {
  const Eigen::VectorXd t = log.col("t");
  const auto dq = log.col(indexed_name("dq", j));
  const auto e = log.col(indexed_name(effort, j));
  std::vector<double> d;
  for (Eigen::Index k = 1; k < log.rows(); ++k) {
    const bool rest = std::abs(dq[k]) < 1e-4 && std::abs(dq[k - 1]) < 1e-4;
    if (rest && t[k] - t[k - 1] < 1.5 * period && std::isfinite(e[k] - e[k - 1]))
      d.push_back(e[k] - e[k - 1]);
  }
  if (d.size() < 10)
    throw Error::at(log.source, 0, indexed_name(effort, j),
                    "too few static rows to estimate the effort noise (the joint must rest, "
                    "|dq| < 1e-4 rad/s, for at least 10 consecutive rows)");
  return robust_std(d) / std::sqrt(2.0);
}

/// σ of the raw pad pressure over live readings (off the rails), 0 without pads.
double pad_noise(const Log& log) {
  // A pad whose offset sits at the sensor's rail (0 kPa) reads 0 again and again: its
  // differences there are clipped noise, not noise, and would bias σ low.
  const double full_scale = SkinSettings<double>{}.full_scale_kpa;
  const auto live = [full_scale](double p) { return p > 0.0 && p < full_scale; };
  std::vector<double> d;
  for (int k = 1; k <= log.pad_count(); ++k) {
    const auto p = log.col(indexed_name("p", k));
    for (Eigen::Index r = 1; r < log.rows(); ++r)
      if (live(p[r]) && live(p[r - 1])) d.push_back(p[r] - p[r - 1]);
  }
  return d.empty() ? 0.0 : robust_std(d) / std::sqrt(2.0);
}

}  // namespace

std::unique_ptr<ReplayEstimator> make_replay_estimator(const ReplaySetup& setup) {
  auto e = std::make_unique<ReplayEstimator>(setup.nominal, setup.pads, setup.parameters);
  e->compensator().inner.load(setup.weights);
  e->set_compensated_joints(compensated_joints(setup.weights, e->joint_count(),
                                               setup.parameters.compensator_min_held_out_gain));
  return e;
}

EstimatorTrace trace_estimator(ReplayEstimator& estimator,
                               const std::vector<ReplaySample>& samples) {
  using S = double;
  const auto T = static_cast<Eigen::Index>(samples.size());
  const int N = estimator.joint_count();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EstimatorTrace tr;
  tr.t = Eigen::VectorXd::Constant(T, nan);
  tr.dq = Eigen::MatrixXd::Constant(T, N, nan);
  tr.inputs = Eigen::MatrixXd::Constant(T, kCompensatorInputsPerJoint * N, nan);
  tr.residual = tr.dq;
  tr.compensation = tr.dq;
  for (auto& e : tr.estimates)
    e = tr.dq;
  tr.proprioceptive = tr.dq;
  tr.external = tr.dq;
  tr.state = Eigen::VectorXi::Constant(T, -1);
  tr.contact = tr.state;
  tr.estimator_contact = tr.state;
  tr.pad = tr.state;
  tr.pad_force = Eigen::VectorXd::Constant(T, nan);
  tr.force_world = Eigen::MatrixXd::Constant(T, 3, nan);
  tr.wrench_valid = tr.state;
  tr.force_tactile = tr.force_world;
  tr.force_proprioceptive = tr.force_world;
  tr.torque_tactile = tr.dq;

  const auto& model = estimator.nominal().model;
  Data<S, Eigen::Dynamic> data(model);
  Jacobian<S, Eigen::Dynamic> J;
  ContactForceSettings<S> no_prior = estimator.parameters().wrench;
  no_prior.prior_floor_n = S(1e9);  // σ_Fn huge: the pad reading does not inform the solve
  no_prior.prior_relative = S(0);

  estimator.reset();
  for (Eigen::Index r = 0; r < T; ++r) {
    const auto& out = estimator.update(samples[static_cast<std::size_t>(r)]);
    if (out.status & (kStatusNonFiniteInput | kStatusStaleTime)) continue;
    tr.t[r] = double(out.t);
    tr.dq.row(r) = samples[static_cast<std::size_t>(r)].dq.transpose();
    tr.inputs.row(r) = estimator.compensator().last_input.transpose();
    tr.residual.row(r) = out.residual.transpose();
    tr.compensation.row(r) = out.compensation.transpose();
    for (int e = 0; e < kTorqueEstimatorCount; ++e) {
      const auto& est = out.estimates[static_cast<std::size_t>(e)];
      for (int j = 0; j < N; ++j)
        tr.estimates[static_cast<std::size_t>(e)](r, j) =
            (est.valid & (1u << j)) ? double(est.residual[j]) : nan;
    }
    const ExternalTorque<S, Eigen::Dynamic> proprio =
        proprioceptive_estimate(out, estimator.parameters());
    tr.proprioceptive.row(r) = proprio.residual.transpose();
    tr.external.row(r) = out.external.residual.transpose();
    tr.state[r] = static_cast<int>(out.state);
    const auto& skin = estimator.skin();
    tr.contact[r] = skin.any_contact() ? 1 : 0;
    tr.estimator_contact[r] = out.contact ? 1 : 0;
    const int pad = skin.most_loaded();
    tr.pad[r] = pad;
    tr.pad_force[r] = pad >= 0 ? double(skin.normal_force(pad)) : 0.0;
    if (out.wrench.pad >= 0) tr.force_world.row(r) = out.wrench.force_world.transpose();
    tr.wrench_valid[r] = out.wrench.pad >= 0 && out.wrench.valid ? 1 : 0;
    tr.torque_tactile.row(r).setZero();
    if (pad >= 0) {
      const auto& g = skin.geometry(pad);
      forward_kinematics(model, data, samples[static_cast<std::size_t>(r)].q);
      const Vector3<S> normal = pad_normal_in_world(data, g);
      tr.force_tactile.row(r) = (-tr.pad_force[r] * normal).transpose();
      point_jacobian(model, data, g.link, pad_point_in_world(data, g), J);
      tr.torque_tactile.row(r) =
          (J.topRows<3>().transpose() * tr.force_tactile.row(r).transpose()).transpose();
      const ContactForce<S> f = estimate_contact_force(J, pad_contact_frame_in_world(data, g),
                                                       proprio.torque, S(0), no_prior);
      tr.force_proprioceptive.row(r) = f.force_world.transpose();
    }
  }
  return tr;
}

SteppedEstimator::SteppedEstimator(const ReplaySetup& setup)
    : estimator_(make_replay_estimator(setup)) {}

SteppedEstimator::~SteppedEstimator() = default;

const EstimatorOutput<double, Eigen::Dynamic>& SteppedEstimator::update(
    const ReplaySample& sample) noexcept {
  return estimator_->update(sample);
}

SensorNoise estimate_sensor_noise(const Log& log, const Eigen::VectorXd& torque_constant,
                                  std::vector<int>* never_rests) {
  SensorNoise noise;
  const std::string effort = log.effort_prefix();
  if (torque_constant.size() != log.joint_count())
    throw Error::at(log.source, 0, "", "torque constants for another joint count");
  const DriveUnits units{effort_unit_of_column(effort), torque_constant};
  const double rate = log.quality.rate_hz;  // the time column's where the metadata contradicts it
  const double period = std::isfinite(rate) && rate > 0 ? 1.0 / rate : 0.0025;
  const int joints = log.joint_count();
  noise.effort.resize(joints);
  noise.effort_step.resize(joints);
  if (never_rests) never_rests->clear();
  for (int j = 0; j < joints; ++j) {
    noise.effort_step[j] = units.to_torque(j, 1.0);
    try {
      noise.effort[j] = units.to_torque(j, effort_noise(log, effort, j + 1, period));
    } catch (const Error&) {
      if (!never_rests) throw;
      never_rests->push_back(j);
      noise.effort[j] = std::numeric_limits<double>::quiet_NaN();
    }
  }
  if (never_rests && !never_rests->empty()) {
    const double largest = noise.effort.array().isFinite().select(noise.effort, 0.0).maxCoeff();
    for (int j : *never_rests)
      noise.effort[j] = largest;
  }
  noise.pad_kpa = pad_noise(log);
  return noise;
}

ReplayParameters estimator_parameters_from_noise(const SensorNoise& noise,
                                                 double pad_gain_kpa_per_n) {
  const auto n = static_cast<int>(noise.effort.size());
  if (noise.effort_step.size() != n)
    throw Error("sensor noise of " + std::to_string(n) + " joints with effort steps of " +
                std::to_string(noise.effort_step.size()));
  ReplayParameters p;
  p.resize(n);
  const int window =
      static_cast<int>(std::lround(p.static_friction.baseline_window_s / p.sample_period_s));
  // The effort is rounded to 1 unit of the log: its variance adds step²/12.
  const ReplayVector sigma =
      (noise.effort.array().square() + noise.effort_step.array().square() / 12.0).sqrt().matrix();
  p.static_dead_band = static_dead_band_from_noise<double, Eigen::Dynamic>(sigma, window);
  if (noise.pad_kpa > 0)
    p.skin.detector = detector_settings_from_noise(noise.pad_kpa, p.sample_period_s, 0.0105);
  p.skin.force_gain = 1.0 / (pad_gain_kpa_per_n * 1000.0 * 0.0025);
  return p;
}

EstimatorTrace replay_estimator(const ReplaySetup& setup,
                                const std::vector<ReplaySample>& samples) {
  return trace_estimator(*make_replay_estimator(setup), samples);
}

ReplayVector speed_envelope(const std::vector<ReplaySample>& samples) {
  ReplayVector v = ReplayVector::Zero(samples.empty() ? 0 : samples.front().dq.size());
  for (const ReplaySample& s : samples)
    if (std::isfinite(s.t) && s.dq.allFinite()) v = v.cwiseMax(s.dq.cwiseAbs());
  return v;
}

ReplayVector acceleration_envelope(const EstimatorTrace& tr) {
  const Eigen::Index n = tr.dq.cols();
  ReplayVector a = ReplayVector::Zero(n);
  const auto ddq = tr.inputs.middleCols(2 * n, n);  // compensator_input
  for (Eigen::Index k = 0; k < tr.rows(); ++k)
    if (ddq.row(k).allFinite()) a = a.cwiseMax(ddq.row(k).transpose().cwiseAbs());
  return a;
}

TransitionSigma<double, Eigen::Dynamic> calibrate_sigma(ReplaySetup& setup,
                                                        const std::vector<ReplaySample>& samples,
                                                        const std::string& source) {
  const auto estimator = make_replay_estimator(setup);
  const auto sigma = calibrate_transition_sigma(*estimator, samples, 0.07, source);
  setup.parameters.nominal_sigma = sigma.nominal;
  setup.parameters.fused_sigma = sigma.fused;
  return sigma;
}

}  // namespace tpf::offline
