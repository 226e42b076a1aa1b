// Realism check of the digital twin (docs/twin.md): simulates a scenario, fits nothing, and
// evaluates the *nominal* model a user starts with — rigid body (true inertial parameters) plus
// the memoryless Stribeck + viscous curve without load terms — on the samples at rest:
//   r = i − (RNEA(q, q̇, 0) + τ_f,Stribeck(q̇))/K_t   [mA],  at rest when |q̇| < 1e-4 rad/s.
// Prints the residual RMSE per joint, its mean after approaching from either side, and writes an
// SVG of one joint's current and true friction around several motion onsets.
//
//   build/release/bin/tpf_twin_realism [scenario.json] [duration_s] [out.svg] [joint 1..4]
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "offline/report/line_plot.hpp"
#include "offline/report/plot_canvas.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/friction/friction_file.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/load_robot.hpp"

namespace {

using namespace tpf::offline;
constexpr int N = 4;  // the realism check runs on the arm4 (data/arm4.robot.json)
using Vec = tpf::JointVector<double, N>;
constexpr double kRestVelocity = 1e-4;    // rad/s, the original work's static threshold
constexpr double kMovingVelocity = 1e-3;  // rad/s, a sample that clearly moves

/// One time series for the onset plot; NaN leaves a gap (e.g. the residual while moving).
struct Trace {
  std::string label, colour;
  std::vector<double> t, y;
};

/// One line plot per panel (report kit), stacked into a single SVG file.
void write_svg(const std::string& path, const std::string& title,
               const std::vector<std::vector<Trace>>& panels,
               const std::vector<std::string>& y_labels) {
  constexpr int kWidth = 900, kPanel = 280;
  std::vector<std::string> plots;
  for (std::size_t p = 0; p < panels.size(); ++p) {
    PlotOptions options;
    options.title = p == 0 ? title : "";
    options.x_label = p + 1 == panels.size() ? "time [s]" : "";
    options.y_label = y_labels[p];
    options.width = kWidth;
    options.height = kPanel;
    std::vector<Series> series;
    for (const Trace& trace : panels[p]) {
      const auto n = static_cast<Eigen::Index>(trace.t.size());
      series.push_back({trace.label, Eigen::Map<const Eigen::VectorXd>(trace.t.data(), n),
                        Eigen::Map<const Eigen::VectorXd>(trace.y.data(), n), trace.colour});
    }
    plots.push_back(line_plot(options, series));
  }
  std::ofstream(path) << standalone_svg(plots, kWidth, kPanel);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string scenario_file =
      argc > 1 ? argv[1] : TPF_BENCH_DATA_DIR "/scenarios/excitation.json";
  const double duration = argc > 2 ? std::stod(argv[2]) : 600.0;
  const std::string svg_path = argc > 3 ? argv[3] : "twin_onsets.svg";
  const int plot_joint = argc > 4 ? std::stoi(argv[4]) - 1 : 1;

  const Scenario scenario = load_scenario(scenario_file);
  const Log log = simulate_to_log(scenario, 1, duration);
  const auto model = tpf::load_robot<double, N>(scenario.robot_file);
  tpf::Data<double, N> data(model);
  auto nominal = tpf::load_stribeck_parameters<double, N>(scenario.friction_file);
  nominal.load_coulomb.setZero();
  nominal.load_viscous.setZero();

  const Eigen::Index rows = log.rows();
  Eigen::MatrixXd residual(rows, N);
  for (Eigen::Index k = 0; k < rows; ++k) {
    Vec q, dq;
    for (int j = 0; j < N; ++j) {
      q[j] = log.col(indexed_name("q", j + 1))(k);
      dq[j] = log.col(indexed_name("dq", j + 1))(k);
    }
    const Vec tau =
        tpf::rnea(model, data, q, dq, Vec::Zero()) + tpf::stribeck_friction(nominal, dq);
    for (int j = 0; j < N; ++j)
      residual(k, j) =
          log.col(indexed_name("i", j + 1))(k) - tau[j] / model.torque_constant[j] * 1000.0;
  }

  std::printf("simulated %.0f s of '%s' (seed 1), %ld rows\n", duration, scenario.name.c_str(),
              static_cast<long>(rows));
  std::printf("nominal model (rigid body + Stribeck, no memory, no load) at rest, per joint:\n");
  std::printf("%6s %9s %12s %14s %14s %10s\n", "joint", "rest [%]", "RMSE [mA]", "mean after + ",
              "mean after - ", "rows");
  double total_sq = 0;
  long total_n = 0;
  for (int j = 0; j < N; ++j) {
    const auto dq = log.col(indexed_name("dq", j + 1));
    double sq = 0, sum_pos = 0, sum_neg = 0;
    long n = 0, n_pos = 0, n_neg = 0;
    int last = 0;
    for (Eigen::Index k = 0; k < rows; ++k) {
      if (std::abs(dq(k)) > kMovingVelocity) last = dq(k) > 0 ? 1 : -1;
      if (std::abs(dq(k)) >= kRestVelocity) continue;
      const double r = residual(k, j);
      sq += r * r;
      ++n;
      if (last > 0) sum_pos += r, ++n_pos;
      if (last < 0) sum_neg += r, ++n_neg;
    }
    total_sq += sq;
    total_n += n;
    std::printf("%6d %9.1f %12.1f %14.1f %14.1f %10ld\n", j + 1, 100.0 * n / rows,
                std::sqrt(sq / n), n_pos ? sum_pos / n_pos : 0.0, n_neg ? sum_neg / n_neg : 0.0, n);
  }
  std::printf("all joints: static RMSE %.1f mA (original work: 280.17 mA)\n",
              std::sqrt(total_sq / total_n));

  // Plot window: the first 12 s stretch after 30 s (past the start-up) with at least 4 onsets.
  const auto t = log.col("t");
  const auto dq = log.col(indexed_name("dq", plot_joint + 1));
  std::vector<double> onsets;
  for (Eigen::Index k = 1; k < rows; ++k)
    if (t(k) > std::min(30.0, 0.5 * duration) && std::abs(dq(k - 1)) < kRestVelocity &&
        std::abs(dq(k)) >= kRestVelocity)
      onsets.push_back(t(k));
  double begin = t(0);
  for (std::size_t a = 0; a + 3 < onsets.size(); ++a)
    if (onsets[a + 3] - onsets[a] < 10.0) {
      begin = std::max(t(0), onsets[a] - 1.0);
      break;
    }
  const double end = begin + 12.0;
  Trace current{"measured current i (mA)", "#1f77b4", {}, {}};
  Trace fric{"true friction gt_fric (mA)", "#d62728", {}, {}};
  Trace res{"nominal residual at rest (mA)", "#2ca02c", {}, {}};
  Trace vel{"velocity dq (mrad/s)", "#333333", {}, {}};
  for (Eigen::Index k = 0; k < rows; ++k) {
    if (t(k) < begin || t(k) > end) continue;
    current.t.push_back(t(k));
    current.y.push_back(log.col(indexed_name("i", plot_joint + 1))(k));
    fric.t.push_back(t(k));
    fric.y.push_back(log.col(indexed_name("gt_fric", plot_joint + 1))(k));
    res.t.push_back(t(k));
    res.y.push_back(std::abs(dq(k)) < kRestVelocity ? residual(k, plot_joint)
                                                    : std::numeric_limits<double>::quiet_NaN());
    vel.t.push_back(t(k));
    vel.y.push_back(1000.0 * dq(k));
  }
  write_svg(svg_path,
            "Simulated (tpf digital twin): joint " + std::to_string(plot_joint + 1) +
                ", current and friction around motion onsets",
            {{current, fric}, {fric, res}, {vel}},
            {"current [mA]", "current [mA]", "velocity [mrad/s]"});
  std::printf("wrote %s (joint %d, %.1f–%.1f s)\n", svg_path.c_str(), plot_joint + 1, begin, end);
  return 0;
}
