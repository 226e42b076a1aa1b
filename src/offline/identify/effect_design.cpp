#include "offline/identify/effect_design.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "offline/effects/effect_columns.hpp"
#include "offline/identify/gram_row_block.hpp"
#include "offline/identify/parallel_halves.hpp"
#include "offline/identify/theta_products.hpp"
#include "tpf/common/error.hpp"
#include "tpf/dynamics/regressor.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/estimation/nominal_model.hpp"

namespace tpf::offline {
template <int N>
struct EffectDesign<N>::Workspace {
  Regressor<double, N> Y = Regressor<double, N>::Zero();  ///< entries not stored stay zero
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> local;  ///< N × max local
};

template <int N>
void EffectDesign<N>::add_group(FeatureGroup group, FillColumns fill) {
  for (std::size_t c = 0; c < group.column_names.size(); ++c)
    group.columns.push_back(features_++);
  groups_.push_back(std::move(group));
  fills_.push_back(fill);
}

template <int N>
template <typename Families>
void EffectDesign<N>::add_families(const DesignContext& context) {
  const bool declared = std::is_same_v<Families, DeclaredColumns>;
  auto offer = [&]<typename Family>(int joint) {
    if (!Family::offered(context, joint)) return;
    GroupSpec spec = Family::group(context, joint);
    bool extrapolates = false;
    if constexpr (requires { Family::kExtrapolatesInQ; }) extrapolates = Family::kExtrapolatesInQ;
    add_group({std::string(Family::key),
               std::move(spec.title),
               joint,
               declared,
               Family::written_to,
               spec.held_column,
               std::move(spec.judged_beside),
               {},
               std::move(spec.column_names),
               extrapolates},
              &Family::template fill<N>);
  };
  for_each_family<Families>([&]<typename Family>() {
    if (Family::kSharedGroupFirst) offer.template operator()<Family>(-1);
  });
  for (int j = 0; j < N; ++j)
    for_each_family<Families>([&]<typename Family>() { offer.template operator()<Family>(j); });
  for_each_family<Families>([&]<typename Family>() {
    if (!Family::kSharedGroupFirst) offer.template operator()<Family>(-1);
  });
}

template <int N>
EffectDesign<N>::EffectDesign(const Model<double, N>& model, const BaseParameters& base,
                              const JointSamples& samples,
                              std::shared_ptr<const SampleRegressors<N>> regressors,
                              CandidateInputs candidates, double static_velocity)
    : model_(model),
      regressors_(std::move(regressors)),
      base_columns_(base.independent),
      candidates_(std::move(candidates)),
      static_velocity_(static_velocity),
      has_temperature_(samples.temperature.cols() == N) {
  const DesignContext context{N, base_columns_, candidates_, has_temperature_};
  check_samples(samples);
  add_families<DeclaredColumns>(context);
  if (candidates_.enabled) {
    if (candidates_.abs_gravity.rows() != samples.size() || candidates_.abs_gravity.cols() != N)
      throw Error::at(samples.source, 0, "", "candidate library: |G(q)| per sample is missing");
    add_families<CandidateColumns>(context);
  }
  index_joint_groups();
}

template <int N>
void EffectDesign<N>::index_joint_groups() {
  local_.assign(N, {});
  joint_groups_.assign(N, {});
  for (int j = 0; j < N; ++j) {
    for (std::size_t g = 0; g < groups_.size(); ++g)
      if (groups_[g].joint == -1 || groups_[g].joint == j) {
        joint_groups_[j].push_back(
            {static_cast<int>(g), fills_[g], static_cast<int>(groups_[g].columns.size())});
        local_[j].insert(local_[j].end(), groups_[g].columns.begin(), groups_[g].columns.end());
      }
    max_local_ = std::max<int>(max_local_, static_cast<int>(local_[j].size()));
  }
}

template <int N>
std::vector<int> EffectDesign<N>::regressor_columns(const std::vector<int>& base_columns,
                                                    bool candidates) {
  std::vector<int> columns = base_columns;
  if (candidates)
    for (int p = 0; p < PayloadColumns::kColumns; ++p)
      columns.push_back(10 * (N - 1) + p);
  return columns;
}

template <int N>
void EffectDesign<N>::check_samples(const JointSamples& samples) const {
  const std::vector<int> needed = regressor_columns(base_columns_, candidates_.enabled);
  if (!regressors_ || regressors_->size() != samples.size() ||
      !std::all_of(needed.begin(), needed.end(),
                   [&](int column) { return regressors_->holds(column); }))
    throw Error::at(samples.source, 0, "",
                    "effect design: the regressors are not those of these samples");
}

template <int N>
std::vector<int> EffectDesign<N>::declared_columns() const {
  std::vector<int> columns;
  for (const FeatureGroup& g : groups_)
    if (g.declared) columns.insert(columns.end(), g.columns.begin(), g.columns.end());
  return columns;
}

template <int N>
void EffectDesign<N>::fill(const JointSamples& s, Eigen::Index k, Workspace& ws,
                           const std::vector<char>& filled) const {
  const JointVector<double, N> q = s.q.row(k).transpose();
  const JointVector<double, N> dq = s.dq.row(k).transpose();
  const JointVector<double, N> ddq = s.ddq.row(k).transpose();
  regressors_->load(k, ws.Y);
  JointVector<double, N> direction, held;
  for (int j = 0; j < N; ++j) {
    const bool moving = std::abs(dq[j]) >= static_velocity_;
    direction[j] = moving ? (dq[j] > 0 ? 1.0 : -1.0) : 0.0;
    held[j] = moving ? 0.0 : s.held_sign(k, j);
  }
  const SampleRow<N> row{
      {q, dq, ddq, model_.gear_ratio}, ws.Y, direction, held, base_columns_, candidates_, s, k};
  for (int j = 0; j < N; ++j) {
    double* out = &ws.local(j, 0);  // row-major workspace: this joint's local features
    for (const JointGroup& g : joint_groups_[j]) {
      if (filled.empty() || filled[static_cast<std::size_t>(g.group)]) g.fill(row, j, out);
      out += g.width;
    }
  }
}

template <int N>
std::vector<char> EffectDesign<N>::groups_in_use(const std::vector<Eigen::VectorXd>& thetas) const {
  std::vector<char> used(groups_.size(), 0);
  for (std::size_t g = 0; g < groups_.size(); ++g)
    for (const Eigen::VectorXd& theta : thetas)
      for (int c : groups_[g].columns)
        used[g] = used[g] || theta[c] != 0.0;
  return used;
}

template <int N>
DesignGrams EffectDesign<N>::accumulate(const JointSamples& s, int stride) const {
  check_samples(s);
  stride = std::max(stride, 1);
  constexpr int kBlock = 256;
  const Eigen::Index n = s.size();
  auto work = [&](Eigen::Index begin, Eigen::Index end, DesignGrams& out) {
    Workspace ws;
    ws.local.resize(N, max_local_);
    // Local Gram and block of rows [features, y, 1] per (joint, regime, split).
    std::vector<Eigen::MatrixXd> gram;
    std::vector<GramRowBlock> buffer;
    for (int j = 0; j < N; ++j)
      for (int b = 0; b < 6; ++b) {
        const int width = static_cast<int>(local_[j].size()) + 2;
        gram.push_back(Eigen::MatrixXd::Zero(width, width));
        buffer.emplace_back(width, kBlock);
      }
    auto flush = [&](int slot) { buffer[slot].add_to_lower(gram[slot]); };
    for (Eigen::Index k = begin; k < end; k += stride) {
      if (!s.valid[k]) continue;
      fill(s, k, ws);
      for (int j = 0; j < N; ++j) {
        const Regime r = s.regimes[j][k];
        if (r == Regime::Invalid) continue;
        const int slot = j * 6 + regime_index(r) * 2 + (s.heldout[k] ? 1 : 0);
        // ws.local is row-major: joint j's features are contiguous.
        buffer[slot].append_augmented(&ws.local(j, 0), s.effort(k, j));
        if (buffer[slot].full()) flush(slot);
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
  check_samples(s);
  const Eigen::Index n = s.size();
  const int m = static_cast<int>(thetas.size());
  std::vector<Eigen::MatrixXd> predictions;  // each n × N, filled below (not copied from one)
  predictions.reserve(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i)
    predictions.emplace_back(n, N);
  // Per joint: local features × parameter sets.
  std::vector<ThetaProducts> local_theta;
  for (int j = 0; j < N; ++j) {
    Eigen::MatrixXd local(static_cast<Eigen::Index>(local_[j].size()), m);
    for (int i = 0; i < m; ++i)
      for (std::size_t a = 0; a < local_[j].size(); ++a)
        local(static_cast<Eigen::Index>(a), i) = thetas[i][local_[j][a]];
    local_theta.emplace_back(local);
  }
  // A group whose coefficients are zero in every θ_i adds only zeros: its features are not
  // computed (they stay zero in the workspace), the products keep their order.
  const std::vector<char> used = groups_in_use(thetas);
  parallel_halves(n, [&](Eigen::Index begin, Eigen::Index end) {
    Workspace ws;
    ws.local.setZero(N, max_local_);
    std::vector<double> values(static_cast<std::size_t>(m));
    for (Eigen::Index k = begin; k < end; ++k) {
      if (!s.valid[k]) {
        for (Eigen::MatrixXd& p : predictions)
          p.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      fill(s, k, ws, used);
      for (int j = 0; j < N; ++j) {
        local_theta[j].apply(&ws.local(j, 0), values.data());  // row-major: joint j's features
        for (int i = 0; i < m; ++i)
          predictions[i](k, j) = values[static_cast<std::size_t>(i)];
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
