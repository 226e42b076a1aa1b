#include "offline/compensator_training/tcn_trainer.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <random>
#include <thread>

#include "offline/compensator_training/progress_bar.hpp"
#include "offline/signal/butterworth.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

[[noreturn]] void fail(std::string_view field, const std::string& message) {
  throw Error::at("TCN training", 0, field, message);
}

void check_options(const TcnTrainOptions& o) {
  const TcnArchitecture& a = o.architecture;
  if (a.inputs < 1 || a.hidden < 1 || a.outputs < 1 || a.kernel < 2 || a.levels < 1 ||
      a.levels > 16) {
    fail("options.architecture", "needs inputs, hidden, outputs ≥ 1, kernel ≥ 2, levels 1…16");
  }
  if (o.window_outputs < 1) fail("options.window_outputs", "must be ≥ 1");
  if (o.batch_windows < 1) fail("options.batch_windows", "must be ≥ 1");
  if (o.threads < 1) fail("options.threads", "must be ≥ 1");
  if (o.max_epochs < 1) fail("options.max_epochs", "must be ≥ 1");
  if (o.validation_block_windows < 1) fail("options.validation_block_windows", "must be ≥ 1");
  if (!(o.validation_fraction > 0.0 && o.validation_fraction < 1.0)) {
    fail("options.validation_fraction", "must lie in (0, 1)");
  }
  if (!(o.weight_low >= 0.0 && o.weight_high >= 0.0 && o.weight_low + o.weight_high > 0.0)) {
    fail("options.weight_low/weight_high", "must be ≥ 0 and not both 0");
  }
}

/// Row ranges [begin, end) of `sequence` whose inputs and residual are all finite.
std::vector<std::pair<Eigen::Index, Eigen::Index>> finite_runs(const TcnSequence& s) {
  std::vector<std::pair<Eigen::Index, Eigen::Index>> runs;
  Eigen::Index begin = 0;
  for (Eigen::Index r = 0; r <= s.inputs.rows(); ++r) {
    const bool finite = r < s.inputs.rows() && s.inputs.row(r).allFinite() &&
                        s.residual.row(r).allFinite() &&
                        (s.weight.size() == 0 || s.weight.row(r).allFinite());
    if (finite) continue;
    if (r > begin) runs.emplace_back(begin, r);
    begin = r + 1;
  }
  return runs;
}

}  // namespace

TcnTrainer::TcnTrainer(const TcnDataset& dataset, const TcnTrainOptions& options)
    : options_(options) {
  check_options(options_);
  const TcnArchitecture& a = options_.architecture;
  const Eigen::Index field = a.receptive_field();

  // Finite runs long enough for one output; NaN/inf rows are skipped by cutting there.
  struct Run {
    const TcnSequence* sequence;
    Eigen::Index begin, end;
  };
  std::vector<Run> runs;
  for (std::size_t i = 0; i < dataset.sequences.size(); ++i) {
    const TcnSequence& s = dataset.sequences[i];
    const std::string name = "sequences[" + std::to_string(i) + "]";
    if (s.inputs.cols() != a.inputs) {
      fail(name + ".inputs", std::to_string(s.inputs.cols()) + " columns, architecture.inputs is " +
                                 std::to_string(a.inputs));
    }
    if (s.residual.cols() != a.outputs) {
      fail(name + ".residual", std::to_string(s.residual.cols()) +
                                   " columns, architecture.outputs is " +
                                   std::to_string(a.outputs));
    }
    if (s.residual.rows() != s.inputs.rows()) {
      fail(name + ".residual", std::to_string(s.residual.rows()) + " rows, inputs have " +
                                   std::to_string(s.inputs.rows()));
    }
    if (s.weight.size() != 0 &&
        (s.weight.rows() != s.inputs.rows() || s.weight.cols() != a.outputs)) {
      fail(name + ".weight", std::to_string(s.weight.rows()) + " × " +
                                 std::to_string(s.weight.cols()) + ", expected " +
                                 std::to_string(s.inputs.rows()) + " × " +
                                 std::to_string(a.outputs) + " or empty");
    }
    if (s.weight.size() != 0 && (s.weight.array() < 0.0).any()) {
      fail(name + ".weight", "a sample weight is negative");
    }
    Eigen::Index finite_rows = 0;
    for (const auto& [begin, end] : finite_runs(s)) {
      finite_rows += end - begin;
      if (end - begin >= field) runs.push_back({&s, begin, end});
    }
    skipped_samples_ += s.inputs.rows() - finite_rows;
  }

  // Normalisation over every usable sample.
  Eigen::Index count = 0;
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(a.inputs);
  Eigen::VectorXd sum_sq = Eigen::VectorXd::Zero(a.inputs);
  for (const Run& r : runs) {
    const auto rows = r.sequence->inputs.middleRows(r.begin, r.end - r.begin);
    sum += rows.colwise().sum().transpose();
    sum_sq += rows.array().square().colwise().sum().matrix().transpose();
    count += rows.rows();
  }
  if (count == 0)
    fail("dataset", "no finite run of at least R = " + std::to_string(field) + " samples");
  input_mean_ = sum / static_cast<double>(count);
  input_std_ =
      (sum_sq / static_cast<double>(count) - input_mean_.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
  for (Eigen::Index c = 0; c < a.inputs; ++c) {
    if (!(input_std_[c] > 1e-9 * (1.0 + std::abs(input_mean_[c])))) input_std_[c] = 1.0;
  }

  // Segments (normalised, channels × time), target split, windows; windows of a run are
  // consecutive and grouped into blocks of validation_block_windows for the held-out choice.
  std::vector<Window> windows;
  std::vector<int> block_of;  // per window
  int blocks = 0;
  for (const Run& r : runs) {
    Segment<double> seg;
    const Eigen::Index length = r.end - r.begin;
    seg.inputs =
        ((r.sequence->inputs.middleRows(r.begin, length).rowwise() - input_mean_.transpose())
             .array()
             .rowwise() /
         input_std_.transpose().array())
            .matrix()
            .transpose();
    seg.low.resize(a.outputs, length);
    const Butterworth2 split =
        Butterworth2::low_pass(options_.split_cutoff_hz, options_.sample_rate_hz);
    for (int o = 0; o < a.outputs; ++o) {
      seg.low.row(o) = filtfilt(split, r.sequence->residual.col(o).segment(r.begin, length),
                                options_.sample_rate_hz / options_.split_cutoff_hz)
                           .transpose();
    }
    seg.high = r.sequence->residual.middleRows(r.begin, length).transpose() - seg.low;
    if (r.sequence->weight.size() != 0) {
      seg.scale = r.sequence->weight.middleRows(r.begin, length).transpose().cwiseSqrt();
    }
    const int index = static_cast<int>(segments_.size());
    int in_run = 0;
    for (Eigen::Index first = field - 1; first < length; first += options_.window_outputs) {
      const Eigen::Index outputs = std::min<Eigen::Index>(options_.window_outputs, length - first);
      const double weight = seg.scale.size() == 0
                                ? static_cast<double>(outputs * a.outputs)
                                : seg.scale.middleCols(first, outputs).squaredNorm();
      if (in_run % options_.validation_block_windows == 0) ++blocks;
      windows.push_back({index, first, outputs, weight});
      block_of.push_back(blocks - 1);
      ++in_run;
    }
    if (options_.single_precision) {
      float_segments_.push_back({seg.inputs.cast<float>(), seg.low.cast<float>(),
                                 seg.high.cast<float>(), seg.scale.cast<float>()});
    }
    segments_.push_back(std::move(seg));
  }
  if (blocks < 2) {
    fail("dataset", "only " + std::to_string(windows.size()) + " window(s) in " +
                        std::to_string(blocks) +
                        " block(s); at least 2 blocks are needed (one held out)");
  }

  // Seeded held-out choice of whole blocks.
  std::mt19937_64 rng(options_.seed);
  std::vector<int> order(static_cast<std::size_t>(blocks));
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  const int held_out = std::clamp<int>(
      static_cast<int>(std::lround(options_.validation_fraction * blocks)), 1, blocks - 1);
  std::vector<bool> held(static_cast<std::size_t>(blocks), false);
  for (int i = 0; i < held_out; ++i)
    held[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])] = true;
  for (std::size_t w = 0; w < windows.size(); ++w) {
    Window window = windows[w];
    const bool is_held = held[static_cast<std::size_t>(block_of[w])];
    // The first window after a boundary between the sets: its input history (R − 1 samples
    // before its first output) would reach into the other set, so its outputs start R − 1 later.
    const bool after_boundary = w > 0 && windows[w - 1].segment == window.segment &&
                                held[static_cast<std::size_t>(block_of[w - 1])] != is_held;
    if (after_boundary) {
      const Eigen::Index shift = std::min<Eigen::Index>(field - 1, window.outputs);
      if (shift == window.outputs) continue;
      const auto& seg = segments_[static_cast<std::size_t>(window.segment)];
      window.first_output += shift;
      window.outputs -= shift;
      window.weight = seg.scale.size() == 0
                          ? static_cast<double>(window.outputs * a.outputs)
                          : seg.scale.middleCols(window.first_output, window.outputs).squaredNorm();
    }
    (is_held ? validation_ : training_).push_back(window);
  }
  if (weight_sum(training_) <= 0.0 || weight_sum(validation_) <= 0.0) {
    fail("dataset", "the training or the held-out windows have zero total sample weight");
  }
}

std::vector<TcnTrainer::WindowSpan> TcnTrainer::window_spans(bool validation) const {
  const Eigen::Index field = options_.architecture.receptive_field();
  std::vector<WindowSpan> spans;
  for (const Window& w : validation ? validation_ : training_)
    spans.push_back(
        {w.segment, w.first_output - (field - 1), w.first_output, w.first_output + w.outputs});
  return spans;
}

std::size_t TcnTrainer::windows_per_epoch(std::size_t windows, int epoch_windows) {
  if (epoch_windows <= 0 || windows <= static_cast<std::size_t>(epoch_windows)) return windows;
  const std::size_t cap = static_cast<std::size_t>(epoch_windows);
  const std::size_t epochs_per_pass = (windows + cap - 1) / cap;
  return windows / epochs_per_pass;
}

double TcnTrainer::weight_sum(const std::vector<Window>& windows) {
  double n = 0.0;
  for (const Window& w : windows)
    n += w.weight;
  return n;
}

double TcnTrainer::sum_loss(const TcnParameters& parameters, const std::vector<Window>& windows,
                            TcnParameters* gradient) const {
  if (options_.single_precision) {
    return sum_loss_in(parameters.cast<float>(), float_segments_, windows, gradient);
  }
  return sum_loss_in(parameters, segments_, windows, gradient);
}

template <typename S>
double TcnTrainer::sum_loss_in(const BasicTcnParameters<S>& parameters,
                               const std::vector<Segment<S>>& segments,
                               const std::vector<Window>& windows, TcnParameters* gradient) const {
  const Eigen::Index field = options_.architecture.receptive_field();
  std::array<double, kChunks> losses{};
  std::vector<BasicTcnParameters<S>> gradients;
  if (gradient != nullptr) {
    gradients.assign(kChunks, zero_tcn_parameters(options_.architecture).cast<S>());
  }

  auto run_chunk = [&](int c) {
    BasicTcnWindowWorkspace<S>& workspace = workspaces<S>()[static_cast<std::size_t>(c)];
    const std::size_t begin = windows.size() * c / kChunks;
    const std::size_t end = windows.size() * (c + 1) / kChunks;
    for (std::size_t i = begin; i < end; ++i) {
      const Window& w = windows[i];
      const Segment<S>& s = segments[w.segment];
      // An empty scale (no weights) gives a 0-column view; it is not passed on.
      const TcnWindowMatrix<S> scale = s.scale.middleCols(std::min(w.first_output, s.scale.cols()),
                                                          s.scale.size() == 0 ? 0 : w.outputs);
      losses[c] += tcn_window_loss<S>(
          parameters, s.inputs.middleCols(w.first_output - (field - 1), w.outputs + field - 1),
          s.low.middleCols(w.first_output, w.outputs), s.high.middleCols(w.first_output, w.outputs),
          options_.weight_low, options_.weight_high, workspace,
          gradient != nullptr ? &gradients[c] : nullptr, s.scale.size() == 0 ? nullptr : &scale);
    }
  };
  const int threads = std::min(options_.threads, kChunks);
  std::vector<std::thread> workers;
  for (int t = 1; t < threads; ++t) {
    workers.emplace_back([&, t] {
      for (int c = t; c < kChunks; c += threads)
        run_chunk(c);
    });
  }
  for (int c = 0; c < kChunks; c += threads)
    run_chunk(c);
  for (auto& w : workers)
    w.join();

  // Fixed reduction order (in double): the result does not depend on scheduling or thread count.
  double total = 0.0;
  for (int c = 0; c < kChunks; ++c)
    total += losses[c];
  if (gradient != nullptr) {
    Eigen::VectorXd sum = flatten(*gradient);
    for (int c = 0; c < kChunks; ++c) {
      TcnParameters chunk = gradients[c].template cast<double>();
      sum += flatten(chunk);
    }
    unflatten(sum, *gradient);
  }
  return total;
}

double TcnTrainer::loss(const TcnParameters& parameters, bool validation) const {
  const std::vector<Window>& windows = validation ? validation_ : training_;
  return sum_loss(parameters, windows, nullptr) / weight_sum(windows);
}

TcnTrainResult TcnTrainer::train(const TcnProgressCallback& progress) {
  return train(init_tcn_parameters(options_.architecture, options_.seed), progress);
}

TcnTrainResult TcnTrainer::train(TcnParameters parameters, const TcnProgressCallback& progress) {
  const TcnArchitecture& a = options_.architecture;
  const TcnArchitecture& s = parameters.architecture;
  if (s.inputs != a.inputs || s.hidden != a.hidden || s.levels != a.levels ||
      s.kernel != a.kernel || s.outputs != a.outputs) {
    fail("start parameters", "architecture differs from options.architecture");
  }
  parameters.input_mean = input_mean_;
  parameters.input_std = input_std_;

  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  std::mt19937_64 rng(options_.seed ^ 0x9e3779b97f4a7c15ULL);
  Eigen::VectorXd theta = flatten(parameters);
  AdamOptimizer adam(theta.size(), options_.adam);
  TcnParameters gradient = zero_tcn_parameters(a);

  TcnTrainResult result;
  result.best = parameters;
  result.best_validation_loss = loss(parameters, true);
  std::vector<Window> order = training_;
  const std::size_t per_epoch = windows_per_epoch(order.size(), options_.epoch_windows);
  std::size_t pass_position = order.size();  // the first epoch shuffles
  std::vector<Window> batch;
  int last_decay = 0;
  for (int epoch = 1; epoch <= options_.max_epochs; ++epoch) {
    if (order.size() - pass_position < per_epoch) {
      std::shuffle(order.begin(), order.end(), rng);
      pass_position = 0;
    }
    const std::size_t epoch_begin = pass_position, epoch_end = pass_position + per_epoch;
    pass_position = epoch_end;
    double epoch_loss = 0.0;
    for (std::size_t first = epoch_begin; first < epoch_end; first += options_.batch_windows) {
      const std::size_t last = std::min(epoch_end, first + options_.batch_windows);
      batch.assign(order.begin() + first, order.begin() + last);
      unflatten(Eigen::VectorXd::Zero(theta.size()), gradient);
      epoch_loss += sum_loss(parameters, batch, &gradient);
      // Normalised by the batch's weight sum (≥ one window's; a zero-weight batch makes no step).
      const double batch_weight = weight_sum(batch);
      if (batch_weight > 0.0) adam.step(theta, flatten(gradient) / batch_weight);
      unflatten(theta, parameters);
    }

    TcnTrainProgress p;
    p.learning_rate = adam.learning_rate();
    p.epoch = epoch;
    p.max_epochs = options_.max_epochs;
    p.train_loss =
        epoch_loss / std::accumulate(order.begin() + epoch_begin, order.begin() + epoch_end, 0.0,
                                     [](double n, const Window& w) { return n + w.weight; });
    p.validation_loss = loss(parameters, true);
    if (p.validation_loss < result.best_validation_loss || result.best_epoch == 0) {
      result.best = parameters;
      result.best_validation_loss = p.validation_loss;
      result.best_epoch = epoch;
      if (!options_.checkpoint_path.empty()) {
        write_tcn_weight_file(options_.checkpoint_path, to_weight_file(result.best));
      }
    }
    const int stale = epoch - std::max(result.best_epoch, last_decay);
    bool converged = false;
    if (options_.decay_patience > 0 && stale >= options_.decay_patience) {
      converged = 0.5 * adam.learning_rate() < options_.min_learning_rate;
      adam.set_learning_rate(0.5 * adam.learning_rate());
      last_decay = epoch;
    }
    p.best_validation_loss = result.best_validation_loss;
    p.best_epoch = result.best_epoch;
    p.elapsed_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    p.remaining_seconds = p.elapsed_seconds / epoch * (options_.max_epochs - epoch);
    const bool out_of_time =
        options_.max_seconds > 0.0 && p.elapsed_seconds >= options_.max_seconds;
    if (options_.max_seconds > 0.0) {
      p.remaining_seconds =
          std::min(p.remaining_seconds, std::max(0.0, options_.max_seconds - p.elapsed_seconds));
    }
    result.stopped_early = epoch - result.best_epoch >= options_.patience || converged;
    result.stopped_on_time = out_of_time && !result.stopped_early && epoch < options_.max_epochs;
    p.last = result.stopped_early || out_of_time || epoch == options_.max_epochs;
    if (p.last) p.remaining_seconds = 0.0;
    result.history.push_back(p);
    if (progress) progress(p);
    if (p.last) break;
  }
  return result;
}

TcnTrainResult train_tcn(const TcnDataset& dataset, const TcnTrainOptions& options,
                         const TcnProgressCallback& progress) {
  return TcnTrainer(dataset, options).train(progress);
}

TcnProgressCallback tcn_progress_bar(std::ostream& out, bool redraw) {
  auto bar = std::make_shared<TerminalProgressBar>(out, 30, redraw);
  // Not a terminal (a log file): a line per network at each third of its epochs and at its end,
  // not one per epoch.
  auto thirds = std::make_shared<std::map<int, int>>();
  auto lock = std::make_shared<std::mutex>();
  return [bar, thirds, lock, redraw](const TcnTrainProgress& p) {
    const std::lock_guard<std::mutex> guard(*lock);
    const double fraction = p.last ? 1.0 : static_cast<double>(p.epoch) / p.max_epochs;
    const int third = static_cast<int>(std::floor(3.0 * fraction));
    const auto seen = thirds->find(p.network);
    if (!redraw && !p.last && (third == 0 || (seen != thirds->end() && seen->second >= third)))
      return;
    (*thirds)[p.network] = third;
    char status[192];
    std::snprintf(status, sizeof status,
                  "net %d  epoch %d/%d  loss %.4g  val %.4g  best %.4g @%d  lr %.2g  %.1f s",
                  p.network + 1, p.epoch, p.max_epochs, p.train_loss, p.validation_loss,
                  p.best_validation_loss, p.best_epoch, p.learning_rate, p.elapsed_seconds);
    bar->update(fraction, status, p.remaining_seconds);
    if (p.last) bar->finish();
  };
}

}  // namespace tpf::offline
