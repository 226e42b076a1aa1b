#include "offline/identify/effect_design.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "offline/identify/parallel_halves.hpp"
#include "tpf/common/error.hpp"
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
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> local;  ///< N × max local
};

template <int N>
void EffectDesign<N>::add_group(FeatureKind kind, std::string key, std::string title, int joint,
                                std::vector<std::string> column_names) {
  FeatureGroup group{kind,
                     std::move(key),
                     std::move(title),
                     joint,
                     kind == FeatureKind::Rigid || kind == FeatureKind::Friction,
                     {},
                     std::move(column_names)};
  for (std::size_t c = 0; c < group.column_names.size(); ++c)
    group.columns.push_back(features_++);
  groups_.push_back(std::move(group));
}

template <int N>
EffectDesign<N>::EffectDesign(const Model<double, N>& model, const BaseParameters& base,
                              const JointSamples& samples, CandidateInputs candidates,
                              double static_velocity)
    : model_(model),
      base_columns_(base.independent),
      candidates_(std::move(candidates)),
      static_velocity_(static_velocity),
      has_temperature_(samples.temperature.cols() == N) {
  using K = FeatureKind;
  std::vector<std::string> rigid;
  for (int c : base_columns_)
    rigid.push_back(regressor_column_name(N, c));
  add_group(K::Rigid, "rigid", "rigid body (base parameters, armature)", -1, rigid);
  for (int j = 0; j < N; ++j) {
    const std::string n = std::to_string(j + 1);
    add_group(K::Friction, "friction", "Coulomb and viscous friction, " + joint_name(j), j,
              {"fc" + n, "fv" + n, "rest" + n});
  }
  if (candidates_.enabled) {
    if (candidates_.abs_gravity.rows() != samples.size() || candidates_.abs_gravity.cols() != N)
      throw Error::at(samples.source, 0, "", "candidate library: |G(q)| per sample is missing");
    std::vector<std::string> payload;
    for (int c = 0; c < 10; ++c)
      payload.push_back("payload_" + regressor_column_name(N, 10 * (N - 1) + c));
    add_group(K::Payload, "payload", "unmodelled payload on the last link", -1, payload);
    for (int j = 0; j < N; ++j) {
      const std::string n = std::to_string(j + 1);
      add_group(K::LoadFriction, "load_friction", "load-dependent friction, " + joint_name(j), j,
                {"alpha_c" + n, "alpha_v" + n, "alpha_rest" + n});
      if (candidates_.ripple_cycles.size() == N && candidates_.ripple_cycles[j] > 0) {
        char title[96];
        std::snprintf(title, sizeof title, "position ripple, %s (%g periods/rev of q)",
                      joint_name(j).c_str(), candidates_.ripple_cycles[j]);
        add_group(K::Ripple, "ripple", title, j, {"ripple_sin" + n, "ripple_cos" + n});
      }
      if (candidates_.ripple_motor_cycles.size() == N && candidates_.ripple_motor_cycles[j] > 0) {
        char title[96];
        std::snprintf(title, sizeof title, "motor-angle ripple, %s (%g periods/motor rev)",
                      joint_name(j).c_str(), candidates_.ripple_motor_cycles[j]);
        add_group(K::RippleMotor, "ripple_motor", title, j, {"motor_sin" + n, "motor_cos" + n});
      }
      if (has_temperature_)
        add_group(K::Thermal, "thermal", "temperature-dependent friction, " + joint_name(j), j,
                  {"beta_v" + n});
      add_group(K::Offset, "offset", "constant offset, " + joint_name(j), j, {"offset" + n});
      add_group(K::Asymmetry, "asymmetric_friction",
                "direction-asymmetric friction (Coulomb, viscous), " + joint_name(j), j,
                {"asym_c" + n, "asym_v" + n});
      add_group(K::Spring, "spring", "joint spring or cable torque (k·q), " + joint_name(j), j,
                {"k" + n});
      if (candidates_.prediction_rate.cols() == N)
        add_group(K::Delay, "delay", "delay between effort and motion, " + joint_name(j), j,
                  {"lead_s" + n});
      if (N > 1) {
        std::vector<std::string> coupling;
        for (int k = 0; k < N; ++k)
          if (k != j) {
            coupling.push_back("cv" + n + "_" + std::to_string(k + 1));
            coupling.push_back("ca" + n + "_" + std::to_string(k + 1));
          }
        add_group(K::Coupling, "coupling", "coupling from other joints' motion, " + joint_name(j),
                  j, coupling);
        std::vector<std::string> neighbour;
        for (int k = 0; k < N; ++k)
          if (k != j) {
            neighbour.push_back("beta" + n + "_" + std::to_string(k + 1));
            neighbour.push_back("gamma" + n + "_" + std::to_string(k + 1));
          }
        add_group(K::NeighbourLoad, "neighbour_load_friction",
                  "friction growing with the other joints' load |G_k|, " + joint_name(j), j,
                  neighbour);
      }
    }
    if (candidates_.prediction_rate.cols() == N && N > 1)
      add_group(K::Delay, "delay", "delay between effort and motion, every joint (one lead)", -1,
                {"lead_s"});
    if (has_temperature_ && candidates_.viscous.size() == N && N > 1)
      add_group(K::Thermal, "thermal",
                "temperature-dependent friction, every joint (one relative change of the viscous "
                "friction per °C)",
                -1, {"beta_v"});
  }
  local_.assign(N, {});
  joint_groups_.assign(N, {});
  for (int j = 0; j < N; ++j) {
    for (std::size_t g = 0; g < groups_.size(); ++g)
      if (groups_[g].joint == -1 || groups_[g].joint == j) {
        joint_groups_[j].push_back(static_cast<int>(g));
        local_[j].insert(local_[j].end(), groups_[g].columns.begin(), groups_[g].columns.end());
      }
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
  using K = FeatureKind;
  const JointVector<double, N> q = s.q.row(k).transpose();
  const JointVector<double, N> dq = s.dq.row(k).transpose();
  const JointVector<double, N> ddq = s.ddq.row(k).transpose();
  compute_regressor(model_, ws.data, q, dq, ddq, ws.Y);
  for (int j = 0; j < N; ++j) {
    const bool moving = std::abs(dq[j]) >= static_velocity_;
    const double sign = moving ? (dq[j] > 0 ? 1.0 : -1.0) : 0.0;
    const double held = moving ? 0.0 : s.held_sign(k, j);
    double* out = &ws.local(j, 0);  // row-major workspace: this joint's local features
    for (int g : joint_groups_[j]) {
      switch (groups_[g].kind) {
        case K::Rigid:
          for (int col : base_columns_)
            *out++ = ws.Y(j, col);
          break;
        case K::Friction:
          *out++ = sign;
          *out++ = dq[j];
          *out++ = held;
          break;
        case K::Payload:
          for (int p = 0; p < 10; ++p)
            *out++ = ws.Y(j, 10 * (N - 1) + p);
          break;
        case K::LoadFriction: {
          const double load = candidates_.abs_gravity(k, j);
          *out++ = load * sign;
          *out++ = load * dq[j];
          *out++ = load * held;
          break;
        }
        case K::Ripple: {
          const double a = candidates_.ripple_cycles[j] * q[j];
          *out++ = std::sin(a);
          *out++ = std::cos(a);
          break;
        }
        case K::RippleMotor: {
          const double a = candidates_.ripple_motor_cycles[j] * model_.gear_ratio[j] * q[j];
          *out++ = std::sin(a);
          *out++ = std::cos(a);
          break;
        }
        case K::Thermal:
          *out++ = (s.temperature(k, j) - candidates_.reference_temperature) * dq[j] *
                   (groups_[g].joint < 0 ? candidates_.viscous[j] : 1.0);
          break;
        case K::Spring:
          *out++ = q[j];
          break;
        case K::Offset:
          *out++ = 1.0;
          break;
        case K::Asymmetry:
          *out++ = std::abs(sign);
          *out++ = std::abs(dq[j]);
          break;
        case K::NeighbourLoad:
          for (int o = 0; o < N; ++o)
            if (o != j) {
              *out++ = candidates_.abs_gravity(k, o) * sign;
              *out++ = candidates_.abs_gravity(k, o) * dq[j];
            }
          break;
        case K::Delay: {
          const double rate = candidates_.prediction_rate(k, j);
          *out++ = std::isfinite(rate) ? rate : 0.0;
          break;
        }
        case K::Coupling:
          for (int o = 0; o < N; ++o)
            if (o != j) {
              *out++ = dq[o];
              *out++ = ddq[o];
            }
          break;
      }
    }
  }
}

template <int N>
DesignGrams EffectDesign<N>::accumulate(const JointSamples& s, int stride) const {
  stride = std::max(stride, 1);
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
    for (Eigen::Index k = begin; k < end; k += stride) {
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
  DesignGrams first(N, features_), second(N, features_);
  if (n == 0) return first;
  parallel_halves(n, [&](Eigen::Index begin, Eigen::Index end) {
    work(begin, end, end == n ? second : first);
  });
  first += second;  // same halves, same order: deterministic
  return first;
}

template <int N>
std::vector<Eigen::MatrixXd> EffectDesign<N>::predict_each(
    const JointSamples& s, const std::vector<Eigen::VectorXd>& thetas) const {
  const Eigen::Index n = s.size();
  const int m = static_cast<int>(thetas.size());
  std::vector<Eigen::MatrixXd> predictions(m, Eigen::MatrixXd(n, N));
  // Per joint: local features × parameter sets.
  std::vector<Eigen::MatrixXd> local_theta(N);
  for (int j = 0; j < N; ++j) {
    local_theta[j].resize(static_cast<Eigen::Index>(local_[j].size()), m);
    for (int i = 0; i < m; ++i)
      for (std::size_t a = 0; a < local_[j].size(); ++a)
        local_theta[j](static_cast<Eigen::Index>(a), i) = thetas[i][local_[j][a]];
  }
  parallel_halves(n, [&](Eigen::Index begin, Eigen::Index end) {
    Workspace ws;
    ws.local.resize(N, max_local_);
    Eigen::RowVectorXd values(m);
    for (Eigen::Index k = begin; k < end; ++k) {
      if (!s.valid[k]) {
        for (Eigen::MatrixXd& p : predictions)
          p.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      fill(s, k, ws);
      for (int j = 0; j < N; ++j) {
        values.noalias() = ws.local.row(j).head(local_theta[j].rows()) * local_theta[j];
        for (int i = 0; i < m; ++i)
          predictions[i](k, j) = values[i];
      }
    }
  });
  return predictions;
}

template <int N>
Eigen::MatrixXd EffectDesign<N>::predict(const JointSamples& s,
                                         const Eigen::VectorXd& theta) const {
  return std::move(predict_each(s, {theta}).front());
}

template class EffectDesign<1>;
template class EffectDesign<2>;
template class EffectDesign<3>;
template class EffectDesign<4>;
template class EffectDesign<5>;
template class EffectDesign<6>;
template class EffectDesign<7>;

}  // namespace tpf::offline
