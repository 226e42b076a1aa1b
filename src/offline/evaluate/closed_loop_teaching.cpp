#include "offline/evaluate/closed_loop_teaching.hpp"

#include <cmath>

#include "offline/evaluate/contact_detection.hpp"
#include "offline/sim/simulate.hpp"
#include "tpf/common/error.hpp"
#include "tpf/estimation/proprioceptive_estimate.hpp"
#include "tpf/model/effort_unit.hpp"

namespace tpf::offline {
namespace {

/// Column indices of a simulated log row (currents i<j> in mA, or the joint torques tau<j> in
/// N·m of a robot with coupled motors) for an estimator sample of `joints` joints and `pads` pads;
/// a current becomes torque with the model's K_t.
struct RowLayout {
  int t = 0;
  std::vector<int> q, dq, i, p;
  bool torque = false;  ///< the effort columns are tau<j> (N·m)
  RowLayout(const std::vector<std::string>& columns, int joints, int pads) {
    const auto find = [&](const std::string& name) {
      for (std::size_t c = 0; c < columns.size(); ++c)
        if (columns[c] == name) return static_cast<int>(c);
      return -1;
    };
    const auto at = [&](const std::string& name) {
      const int c = find(name);
      if (c < 0) throw Error::at("simulated row", 0, name, "column missing");
      return c;
    };
    t = at("t");
    torque = find("i1") < 0 && find("tau1") >= 0;
    for (int j = 0; j < joints; ++j) {
      q.push_back(at(indexed_name("q", j + 1)));
      dq.push_back(at(indexed_name("dq", j + 1)));
      i.push_back(at(indexed_name(torque ? "tau" : "i", j + 1)));
    }
    for (int k = 0; k < pads; ++k)
      p.push_back(at(indexed_name("p", k + 1)));
  }
  ReplaySample sample(std::span<const double> row,
                      const Model<double, Eigen::Dynamic>& model) const {
    ReplaySample s;
    s.resize(static_cast<int>(q.size()), static_cast<int>(p.size()));
    s.t = row[static_cast<std::size_t>(t)];
    for (std::size_t j = 0; j < q.size(); ++j) {
      const auto e = static_cast<Eigen::Index>(j);
      s.q[e] = row[static_cast<std::size_t>(q[j])];
      s.dq[e] = row[static_cast<std::size_t>(dq[j])];
      s.effort[e] = row[static_cast<std::size_t>(i[j])];
    }
    if (!torque) s.effort = torque_from_current(model, s.effort);
    for (std::size_t k = 0; k < p.size(); ++k)
      s.pressure[static_cast<Eigen::Index>(k)] = row[static_cast<std::size_t>(p[k])];
    return s;
  }
};

}  // namespace

Eigen::MatrixXd ideal_admittance_velocity(const Eigen::VectorXd& t, const Eigen::MatrixXd& tau,
                                          const Eigen::VectorXd& contact,
                                          const TeachingConfig& config) {
  Eigen::MatrixXd v = Eigen::MatrixXd::Zero(t.size(), tau.cols());
  for (Eigen::Index k = 1; k < t.size(); ++k) {
    const double dt = t[k] - t[k - 1];
    const bool on = contact[k - 1] != 0.0;
    for (Eigen::Index j = 0; j < tau.cols(); ++j) {
      const double input = on ? tau(k - 1, j) : 0.0;
      v(k, j) = v(k - 1, j) +
                dt * (input - config.admittance_damping * v(k - 1, j)) / config.admittance_inertia;
    }
  }
  return v;
}

void score_teaching_loop(const TeachingConfig& config, const Eigen::MatrixXd& estimate,
                         TeachingLoop& loop) {
  const Log& log = loop.log;
  const Eigen::VectorXd t = log.col("t"), contact = log.col("gt_contact");
  const auto joints = static_cast<int>(estimate.cols());
  Eigen::MatrixXd truth(log.rows(), joints), dq(log.rows(), joints);
  for (int j = 0; j < joints; ++j) {
    truth.col(j) = log.col(indexed_name("gt_tau_ext", j + 1));
    dq.col(j) = log.col(indexed_name("dq", j + 1));
  }
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(joints);
  long rows = 0;
  for (Eigen::Index k = 0; k < log.rows(); ++k) {
    if (contact[k] == 0.0 || !estimate.row(k).allFinite()) continue;
    sum += (estimate.row(k) - truth.row(k)).transpose().cwiseAbs2();
    ++rows;
  }
  loop.torque_rmse = (sum / double(std::max(rows, 1L))).cwiseSqrt();

  const Eigen::MatrixXd ideal = ideal_admittance_velocity(t, truth, contact, config);
  Eigen::MatrixXd force(log.rows(), 3);
  force << log.col("gt_fx"), log.col("gt_fy"), log.col("gt_fz");
  double over = 0, under = 0;
  for (const ContactSpan& e : contact_events(contact, force)) {
    for (int j = 0; j < joints; ++j) {
      double peak_ideal = 0, peak = 0;
      for (Eigen::Index k = e.first; k <= e.last && t[k] - t[e.first] <= 0.5; ++k) {
        peak_ideal = std::max(peak_ideal, std::abs(ideal(k, j)));
        peak = std::max(peak, std::abs(dq(k, j)));
      }
      if (peak_ideal < 0.05) continue;
      ++loop.onsets;
      const double change = 100.0 * (peak - peak_ideal) / peak_ideal;
      if (change >= 0) {
        over += change;
        ++loop.overshoots;
      } else {
        under -= change;
        ++loop.undershoots;
      }
    }
  }
  loop.mean_overshoot_percent = loop.overshoots ? over / loop.overshoots : 0.0;
  loop.mean_undershoot_percent = loop.undershoots ? under / loop.undershoots : 0.0;
}

std::array<TeachingLoop, 2> closed_loop_teaching(const ReplaySetup& setup, const Scenario& scenario,
                                                 std::uint64_t seed, double duration_s) {
  if (scenario.kind != Scenario::Kind::kTeaching)
    throw Error::at(scenario.file, 0, "kind", "closed-loop teaching needs a teaching scenario");
  std::array<TeachingLoop, 2> loops;
  loops[0].name = "nominal, no compensator (proprioceptive)";
  loops[1].name = "fusion with the compensator";
  const int pads = static_cast<int>(setup.pads.size());
  const int joints = setup.nominal.model.joint_count();
  const RowLayout layout(simulation_columns(scenario), joints, pads);
  for (int mode = 0; mode < 2; ++mode) {
    TeachingLoop& loop = loops[static_cast<std::size_t>(mode)];
    std::vector<TwinVector> estimates;
    SteppedEstimator estimator(setup);
    const auto source = [&](std::span<const double> row) -> TwinVector {
      const auto& out = estimator.update(layout.sample(row, setup.nominal.model));
      const TwinVector tau =
          mode == 0 ? proprioceptive_estimate(out, setup.parameters).torque : out.external.torque;
      estimates.push_back(tau);
      return tau;
    };
    loop.log = simulate_to_log(scenario, seed, duration_s, source);
    loop.log.source =
        "closed-loop teaching, " + loop.name + " (simulated, seed " + std::to_string(seed) + ")";
    Eigen::MatrixXd estimate(loop.log.rows(), joints);
    for (Eigen::Index k = 0; k < estimate.rows(); ++k)
      estimate.row(k) = estimates[static_cast<std::size_t>(k)].transpose();
    score_teaching_loop(scenario.teaching, estimate, loop);
  }
  return loops;
}

}  // namespace tpf::offline
