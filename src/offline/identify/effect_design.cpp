#include "offline/identify/effect_design.hpp"

#include <cmath>
#include <thread>

#include "tpf/dynamics/regressor.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/estimation/nominal_model.hpp"

namespace tpf::offline {
namespace {

std::string joint_name(int j) {
  return "joint " + std::to_string(j + 1);
}

int regime_index(Regime r) {
  return static_cast<int>(r);
}  // Static 0, StaticToKinetic 1, Moving 2

}  // namespace

template <int N>
struct EffectDesign<N>::Workspace {
  Data<double, N> data;
  Regressor<double, N> Y;
  Eigen::MatrixXd local;
};

template <int N>
void EffectDesign<N>::add_group(FeatureGroup group, int count) {
  for (int c = 0; c < count; ++c)
    group.columns.push_back(features_++);
  groups_.push_back(std::move(group));
}

template <int N>
EffectDesign<N>::EffectDesign(const Model<double, N>& model, const BaseParameters& base,
                              const Eigen::VectorXd& effort_per_newton_metre,
                              const JointSamples& samples, CandidateInputs candidates,
                              double static_velocity)
    : model_(model),
      base_columns_(base.independent),
      scale_(effort_per_newton_metre),
      candidates_(std::move(candidates)),
      static_velocity_(static_velocity),
      has_temperature_(samples.temperature.cols() == N) {
  FeatureGroup rigid{"rigid", "rigid body (base parameters, armature)", -1, true, {}, {}};
  for (int c : base_columns_)
    rigid.column_names.push_back(regressor_column_name(N, c));
  add_group(rigid, base.size());
  for (int j = 0; j < N; ++j) {
    const std::string n = std::to_string(j + 1);
    add_group({"friction",
               "Coulomb and viscous friction, " + joint_name(j),
               j,
               true,
               {},
               {"fc" + n, "fv" + n, "rest" + n}},
              3);
  }
  if (candidates_.enabled) {
    FeatureGroup payload{"payload", "unmodelled payload on the last link", -1, false, {}, {}};
    for (int c = 0; c < 10; ++c)
      payload.column_names.push_back("payload_" + regressor_column_name(N, 10 * (N - 1) + c));
    add_group(payload, 10);
    for (int j = 0; j < N; ++j) {
      const std::string n = std::to_string(j + 1);
      add_group({"load_friction",
                 "load-dependent friction, " + joint_name(j),
                 j,
                 false,
                 {},
                 {"alpha_c" + n, "alpha_v" + n, "alpha_rest" + n}},
                3);
      if (candidates_.ripple_cycles.size() == N && candidates_.ripple_cycles[j] > 0) {
        char title[96];
        std::snprintf(title, sizeof title, "position ripple, %s (%g periods/rev of q)",
                      joint_name(j).c_str(), candidates_.ripple_cycles[j]);
        add_group({"ripple", title, j, false, {}, {"ripple_sin" + n, "ripple_cos" + n}}, 2);
      }
      if (candidates_.ripple_motor_cycles.size() == N && candidates_.ripple_motor_cycles[j] > 0) {
        char title[96];
        std::snprintf(title, sizeof title, "motor-angle ripple, %s (%g periods/motor rev)",
                      joint_name(j).c_str(), candidates_.ripple_motor_cycles[j]);
        add_group({"ripple_motor", title, j, false, {}, {"motor_sin" + n, "motor_cos" + n}}, 2);
      }
      if (has_temperature_)
        add_group({"thermal",
                   "temperature-dependent friction, " + joint_name(j),
                   j,
                   false,
                   {},
                   {"beta_v" + n}},
                  1);
      add_group({"spring",
                 "joint spring or cable torque (k·q + offset), " + joint_name(j),
                 j,
                 false,
                 {},
                 {"k" + n, "offset" + n}},
                2);
      if (candidates_.prediction_rate.cols() == N)
        add_group({"delay",
                   "delay between effort and motion, " + joint_name(j),
                   j,
                   false,
                   {},
                   {"lead_s" + n}},
                  1);
      if (N > 1) {
        FeatureGroup coupling{
            "coupling", "coupling from other joints' motion, " + joint_name(j), j, false, {}, {}};
        for (int k = 0; k < N; ++k)
          if (k != j) {
            coupling.column_names.push_back("cv" + n + "_" + std::to_string(k + 1));
            coupling.column_names.push_back("ca" + n + "_" + std::to_string(k + 1));
          }
        add_group(coupling, 2 * (N - 1));
      }
    }
  }
  local_.assign(N, {});
  for (int j = 0; j < N; ++j) {
    for (const FeatureGroup& g : groups_)
      if (g.joint == -1 || g.joint == j)
        local_[j].insert(local_[j].end(), g.columns.begin(), g.columns.end());
    max_local_ = std::max<int>(max_local_, static_cast<int>(local_[j].size()));
  }
}

template <int N>
std::vector<int> EffectDesign<N>::declared_columns() const {
  std::vector<int> columns;
  for (const FeatureGroup& g : groups_)
    if (g.declared) columns.insert(columns.end(), g.columns.begin(), g.columns.end());
  return columns;
}

template <int N>
void EffectDesign<N>::fill(const JointSamples& s, Eigen::Index k, Workspace& ws) const {
  const JointVector<double, N> q = s.q.row(k).transpose();
  const JointVector<double, N> dq = s.dq.row(k).transpose();
  const JointVector<double, N> ddq = s.ddq.row(k).transpose();
  compute_regressor(model_, ws.data, q, dq, ddq, ws.Y);
  JointVector<double, N> abs_gravity = JointVector<double, N>::Zero();
  if (candidates_.enabled) abs_gravity = compute_gravity(model_, ws.data, q).cwiseAbs();
  for (int j = 0; j < N; ++j) {
    const bool moving = std::abs(dq[j]) >= static_velocity_;
    const double sign = moving ? (dq[j] > 0 ? 1.0 : -1.0) : 0.0;
    const double held = moving ? 0.0 : s.held_sign(k, j);
    int c = 0;
    auto out = [&](double v) { ws.local(j, c++) = v; };
    for (const FeatureGroup& g : groups_) {
      if (g.joint != -1 && g.joint != j) continue;
      const std::string& key = g.key;
      if (key == "rigid") {
        for (int col : base_columns_)
          out(ws.Y(j, col) * scale_[j]);
      } else if (key == "friction") {
        out(sign);
        out(dq[j]);
        out(held);
      } else if (key == "payload") {
        for (int p = 0; p < 10; ++p)
          out(ws.Y(j, 10 * (N - 1) + p) * scale_[j]);
      } else if (key == "load_friction") {
        out(abs_gravity[j] * sign);
        out(abs_gravity[j] * dq[j]);
        out(abs_gravity[j] * held);
      } else if (key == "ripple") {
        const double a = candidates_.ripple_cycles[j] * q[j];
        out(std::sin(a));
        out(std::cos(a));
      } else if (key == "ripple_motor") {
        const double a = candidates_.ripple_motor_cycles[j] * model_.gear_ratio[j] * q[j];
        out(std::sin(a));
        out(std::cos(a));
      } else if (key == "thermal") {
        const double dt = s.temperature(k, j) - candidates_.reference_temperature;
        out(dt * dq[j]);
      } else if (key == "spring") {
        out(q[j]);
        out(1.0);
      } else if (key == "delay") {
        const double rate = candidates_.prediction_rate(k, j);
        out(std::isfinite(rate) ? rate : 0.0);
      } else if (key == "coupling") {
        for (int o = 0; o < N; ++o)
          if (o != j) {
            out(dq[o]);
            out(ddq[o]);
          }
      }
    }
  }
}

template <int N>
DesignGrams EffectDesign<N>::accumulate(const JointSamples& s) const {
  constexpr int kBlock = 256;
  const Eigen::Index n = s.size();
  auto work = [&](Eigen::Index begin, Eigen::Index end, DesignGrams& out) {
    Workspace ws;
    ws.local.resize(N, max_local_);
    // Local Gram and row buffer per (joint, regime, split).
    std::vector<Eigen::MatrixXd> gram, buffer;
    std::vector<int> fill_count(N * 6, 0);
    for (int j = 0; j < N; ++j)
      for (int b = 0; b < 6; ++b) {
        const int width = static_cast<int>(local_[j].size()) + 2;
        gram.push_back(Eigen::MatrixXd::Zero(width, width));
        buffer.push_back(Eigen::MatrixXd::Zero(kBlock, width));
      }
    auto flush = [&](int slot) {
      if (fill_count[slot] == 0) return;
      const auto rows = buffer[slot].topRows(fill_count[slot]);
      gram[slot].selfadjointView<Eigen::Lower>().rankUpdate(rows.transpose());
      fill_count[slot] = 0;
    };
    for (Eigen::Index k = begin; k < end; ++k) {
      if (!s.valid[k]) continue;
      fill(s, k, ws);
      for (int j = 0; j < N; ++j) {
        const Regime r = s.regimes[j][k];
        if (r == Regime::Invalid) continue;
        const int slot = j * 6 + regime_index(r) * 2 + (s.heldout[k] ? 1 : 0);
        const int width = static_cast<int>(local_[j].size());
        auto row = buffer[slot].row(fill_count[slot]);
        row.head(width) = ws.local.row(j).head(width);
        row[width] = s.effort(k, j);
        row[width + 1] = 1.0;
        if (++fill_count[slot] == kBlock) flush(slot);
      }
    }
    out = DesignGrams(N, features_);
    for (int j = 0; j < N; ++j)
      for (int b = 0; b < 6; ++b) {
        const int slot = j * 6 + b;
        flush(slot);
        Eigen::MatrixXd local = gram[slot].selfadjointView<Eigen::Lower>();
        std::vector<int> map = local_[j];
        map.push_back(features_);
        map.push_back(features_ + 1);
        Eigen::MatrixXd& g = out.at(j, b / 2, b % 2);
        for (std::size_t a = 0; a < map.size(); ++a)
          for (std::size_t c = 0; c < map.size(); ++c)
            g(map[a], map[c]) += local(a, c);
      }
  };
  DesignGrams first, second;
  const Eigen::Index middle = n / 2;
  std::thread helper([&] { work(middle, n, second); });
  work(0, middle, first);
  helper.join();
  first += second;
  return first;
}

template <int N>
Eigen::MatrixXd EffectDesign<N>::predict(const JointSamples& s,
                                         const Eigen::VectorXd& theta) const {
  const Eigen::Index n = s.size();
  Eigen::MatrixXd prediction(n, N);
  std::vector<Eigen::VectorXd> local_theta(N);
  for (int j = 0; j < N; ++j) {
    local_theta[j].resize(static_cast<Eigen::Index>(local_[j].size()));
    for (std::size_t a = 0; a < local_[j].size(); ++a)
      local_theta[j][a] = theta[local_[j][a]];
  }
  auto work = [&](Eigen::Index begin, Eigen::Index end) {
    Workspace ws;
    ws.local.resize(N, max_local_);
    for (Eigen::Index k = begin; k < end; ++k) {
      if (!s.valid[k]) {
        prediction.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      fill(s, k, ws);
      for (int j = 0; j < N; ++j)
        prediction(k, j) = ws.local.row(j).head(local_theta[j].size()).dot(local_theta[j]);
    }
  };
  std::thread helper([&] { work(n / 2, n); });
  work(0, n / 2);
  helper.join();
  return prediction;
}

template class EffectDesign<1>;
template class EffectDesign<2>;
template class EffectDesign<3>;
template class EffectDesign<4>;
template class EffectDesign<5>;
template class EffectDesign<6>;

}  // namespace tpf::offline
