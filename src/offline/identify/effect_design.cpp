#include "offline/identify/effect_design.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "offline/effects/effect_columns.hpp"
#include "offline/fit/gram_row_block.hpp"
#include "offline/fit/parallel_halves.hpp"
#include "offline/fit/theta_products.hpp"
#include "tpf/common/error.hpp"
#include "tpf/dynamics/regressor.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/estimation/nominal_model.hpp"

namespace tpf::offline {
/// A thread's scratch of fill(), sized once for the design's joint count: nothing in it is
/// allocated per sample.
struct EffectDesign::Workspace {
  explicit Workspace(int joints)
      : Y(Eigen::MatrixXd::Zero(joints, 13 * joints)),
        q(joints),
        dq(joints),
        ddq(joints),
        direction(joints),
        held(joints) {}
  Eigen::MatrixXd Y;  ///< N × 13N; entries not stored stay zero
  Eigen::VectorXd q, dq, ddq, direction, held;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> local;  ///< N × max local
};

void EffectDesign::add_group(FeatureGroup group, FillColumns fill, int variant) {
  for (std::size_t c = 0; c < group.column_names.size(); ++c)
    group.columns.push_back(features_++);
  groups_.push_back(std::move(group));
  fills_.push_back(fill);
  variants_.push_back(variant);
}

namespace {
/// A family's fill() as EffectDesign's FillColumns (one group per joint or every joint).
template <typename Family>
void fill_family(const SampleRow& row, int joint, int, double* out) {
  Family::fill(row, joint, out);
}
template <typename Family>
concept SeveralGroups = requires(const DesignContext& c) {
  Family::variants(c);
};
}  // namespace

template <typename Families>
void EffectDesign::add_families(const DesignContext& context) {
  const bool declared = std::is_same_v<Families, DeclaredColumns>;
  // One group of the family's spec: for `joint` (−1: every joint or several), filled by `fill`.
  auto add_spec = [&]<typename Family>(GroupSpec spec, int joint, bool extrapolates,
                                       FillColumns fill, int variant) {
    add_group({std::string(Family::key),
               std::move(spec.title),
               joint,
               declared,
               Family::written_to,
               spec.held_column,
               std::move(spec.judged_beside),
               {},
               std::move(spec.column_names),
               extrapolates,
               spec.indistinct_from_beside,
               std::move(spec.joints),
               std::move(spec.dissipative)},
              fill, variant);
  };
  // A candidate on a joint whose effort channel is dead has nothing to be fitted to.
  const auto dead = [&](int joint) {
    return !declared && joint >= 0 &&
           static_cast<std::size_t>(joint) < context.inputs.dead_joints.size() &&
           context.inputs.dead_joints[static_cast<std::size_t>(joint)];
  };
  auto offer = [&]<typename Family>(int joint) {
    if constexpr (SeveralGroups<Family>) {
      if (joint >= 0) return;
      for (int v = 0; v < Family::variants(context); ++v) {
        GroupSpec spec = Family::group(context, v);
        if (std::none_of(spec.joints.begin(), spec.joints.end(), dead))
          add_spec.template operator()<Family>(std::move(spec), -1, false, &Family::fill, v);
      }
    } else {
      if (dead(joint) || !Family::offered(context, joint)) return;
      bool extrapolates = false;
      if constexpr (requires { Family::kExtrapolatesInQ; }) extrapolates = Family::kExtrapolatesInQ;
      add_spec.template operator()<Family>(Family::group(context, joint), joint, extrapolates,
                                           &fill_family<Family>, 0);
    }
  };
  for_each_family<Families>([&]<typename Family>() {
    if (Family::kSharedGroupFirst) offer.template operator()<Family>(-1);
  });
  for (int j = 0; j < joints_; ++j)
    for_each_family<Families>([&]<typename Family>() { offer.template operator()<Family>(j); });
  for_each_family<Families>([&]<typename Family>() {
    if (!Family::kSharedGroupFirst) offer.template operator()<Family>(-1);
  });
}

EffectDesign::EffectDesign(const ModelX& model, const BaseParameters& base,
                           const JointSamples& samples,
                           std::shared_ptr<const SampleRegressors> regressors,
                           CandidateInputs candidates, double static_velocity)
    : model_(model),
      joints_(model.joint_count()),
      regressors_(std::move(regressors)),
      base_columns_(base.independent),
      candidates_(std::move(candidates)),
      static_velocity_(static_velocity),
      has_temperature_(samples.temperature.cols() == joints_) {
  const DesignContext context{joints_, base_columns_, candidates_, has_temperature_, model.coupled};
  check_samples(samples);
  add_families<DeclaredColumns>(context);
  if (candidates_.enabled) {
    if (candidates_.abs_gravity.rows() != samples.size() ||
        candidates_.abs_gravity.cols() != joints_)
      throw Error::at(samples.source, 0, "", "candidate library: |G(q)| per sample is missing");
    add_families<CandidateColumns>(context);
  }
  index_joint_groups();
}

void EffectDesign::index_joint_groups() {
  local_.assign(static_cast<std::size_t>(joints_), {});
  joint_groups_.assign(static_cast<std::size_t>(joints_), {});
  for (int j = 0; j < joints_; ++j) {
    for (std::size_t g = 0; g < groups_.size(); ++g)
      if (acts_on(groups_[g], j)) {
        joint_groups_[j].push_back({static_cast<int>(g), fills_[g],
                                    static_cast<int>(groups_[g].columns.size()), variants_[g]});
        local_[j].insert(local_[j].end(), groups_[g].columns.begin(), groups_[g].columns.end());
      }
    max_local_ = std::max<int>(max_local_, static_cast<int>(local_[j].size()));
  }
}

std::vector<int> EffectDesign::regressor_columns(int joints, const std::vector<int>& base_columns,
                                                 bool candidates, bool motor_friction) {
  std::vector<int> columns = base_columns;
  if (motor_friction)
    for (int c = 11 * joints; c < 13 * joints; ++c)
      columns.push_back(c);
  if (candidates)
    for (int p = 0; p < PayloadColumns::kColumns; ++p)
      columns.push_back(10 * (joints - 1) + p);
  return columns;
}

void EffectDesign::check_samples(const JointSamples& samples) const {
  const std::vector<int> needed = regressor_columns(joints_, base_columns_, candidates_.enabled);
  if (!regressors_ || regressors_->size() != samples.size() ||
      !std::all_of(needed.begin(), needed.end(),
                   [&](int column) { return regressors_->holds(column); }))
    throw Error::at(samples.source, 0, "",
                    "effect design: the regressors are not those of these samples");
}

std::vector<int> EffectDesign::declared_columns() const {
  std::vector<int> columns;
  for (const FeatureGroup& g : groups_)
    if (g.declared) columns.insert(columns.end(), g.columns.begin(), g.columns.end());
  return columns;
}

void EffectDesign::fill(const JointSamples& s, Eigen::Index k, Workspace& ws,
                        const std::vector<char>& filled) const {
  ws.q = s.q.row(k).transpose();
  ws.dq = s.dq.row(k).transpose();
  ws.ddq = s.ddq.row(k).transpose();
  regressors_->load(k, ws.Y);
  for (int j = 0; j < joints_; ++j) {
    const bool moving = std::abs(ws.dq[j]) >= static_velocity_;
    ws.direction[j] = moving ? (ws.dq[j] > 0 ? 1.0 : -1.0) : 0.0;
    ws.held[j] = moving ? 0.0 : s.held_sign(k, j);
  }
  const SampleRow row{{ws.q, ws.dq, ws.ddq, model_.gear_ratio},
                      ws.Y,
                      ws.direction,
                      ws.held,
                      base_columns_,
                      candidates_,
                      s,
                      k};
  for (int j = 0; j < joints_; ++j) {
    double* out = &ws.local(j, 0);  // row-major workspace: this joint's local features
    for (const JointGroup& g : joint_groups_[j]) {
      if (filled.empty() || filled[static_cast<std::size_t>(g.group)])
        g.fill(row, j, g.variant, out);
      out += g.width;
    }
  }
}

std::vector<char> EffectDesign::groups_in_use(const std::vector<Eigen::VectorXd>& thetas) const {
  std::vector<char> used(groups_.size(), 0);
  for (std::size_t g = 0; g < groups_.size(); ++g)
    for (const Eigen::VectorXd& theta : thetas)
      for (int c : groups_[g].columns)
        used[g] = used[g] || theta[c] != 0.0;
  return used;
}

DesignGrams EffectDesign::accumulate(const JointSamples& s) const {
  check_samples(s);
  constexpr int kBlock = 256;
  const Eigen::Index n = s.size();
  auto work = [&](Eigen::Index begin, Eigen::Index end, DesignGrams& out) {
    Workspace ws(joints_);
    ws.local.resize(joints_, max_local_);
    // Local Gram and block of rows [features, y, 1] per (joint, regime, split).
    std::vector<Eigen::MatrixXd> gram;
    std::vector<GramRowBlock> buffer;
    for (int j = 0; j < joints_; ++j)
      for (int b = 0; b < 6; ++b) {
        const int width = static_cast<int>(local_[j].size()) + 2;
        gram.push_back(Eigen::MatrixXd::Zero(width, width));
        buffer.emplace_back(width, kBlock);
      }
    auto flush = [&](int slot) { buffer[slot].add_to_lower(gram[slot]); };
    for (Eigen::Index k = begin; k < end; ++k) {
      if (!s.valid[k]) continue;
      fill(s, k, ws);
      for (int j = 0; j < joints_; ++j) {
        const Regime r = s.regimes[j][k];
        if (r == Regime::Invalid) continue;
        const int slot = j * 6 + regime_index(r) * 2 + (s.heldout[k] ? 1 : 0);
        // ws.local is row-major: joint j's features are contiguous.
        buffer[slot].append_augmented(&ws.local(j, 0), s.effort(k, j));
        if (buffer[slot].full()) flush(slot);
      }
    }
    out = DesignGrams(joints_, features_);
    for (int j = 0; j < joints_; ++j)
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
  DesignGrams first(joints_, features_), second(joints_, features_);
  if (n == 0) return first;
  parallel_halves(n, [&](Eigen::Index begin, Eigen::Index end) {
    work(begin, end, end == n ? second : first);
  });
  first += second;  // same halves, same order: deterministic
  return first;
}

std::vector<Eigen::MatrixXd> EffectDesign::predict_each(
    const JointSamples& s, const std::vector<Eigen::VectorXd>& thetas) const {
  check_samples(s);
  const Eigen::Index n = s.size();
  const int m = static_cast<int>(thetas.size());
  std::vector<Eigen::MatrixXd> predictions;  // each n × N, filled below (not copied from one)
  predictions.reserve(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i)
    predictions.emplace_back(n, joints_);
  // Per joint: local features × parameter sets.
  std::vector<ThetaProducts> local_theta;
  for (int j = 0; j < joints_; ++j) {
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
    Workspace ws(joints_);
    ws.local.setZero(joints_, max_local_);
    std::vector<double> values(static_cast<std::size_t>(m));
    for (Eigen::Index k = begin; k < end; ++k) {
      if (!s.valid[k]) {
        for (Eigen::MatrixXd& p : predictions)
          p.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      fill(s, k, ws, used);
      for (int j = 0; j < joints_; ++j) {
        local_theta[j].apply(&ws.local(j, 0), values.data());  // row-major: joint j's features
        for (int i = 0; i < m; ++i)
          predictions[i](k, j) = values[static_cast<std::size_t>(i)];
      }
    }
  });
  return predictions;
}

Eigen::MatrixXd EffectDesign::predict(const JointSamples& s, const Eigen::VectorXd& theta) const {
  return std::move(predict_each(s, {theta}).front());
}

}  // namespace tpf::offline
