// Frozen-sensor detection: a live reading carries noise, so it never repeats bit for bit for long.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>

#include "tpf/common/types.hpp"

namespace tpf {

/// Flags channels whose reading has repeated exactly for more than `limit` consecutive samples.
/// A channel is a row of C components (e.g. a joint's q, q̇ and effort, or a pad's pressure); it
/// repeats when every component equals the previous sample's. A live PH54 current (a few mA of
/// noise on 1 mA steps) or pad pressure (0.03 kPa on 0.01 kPa ADC steps) never repeats for
/// hundreds of samples; a stalled bus, a stuck driver buffer or a blocked pad does. NaN never
/// equals anything, so a missing value ends a run. Per cycle: no allocation, no exception.
/// M may be Eigen::Dynamic (≤ 32 channels, sized by reset()).
template <typename S, int M, int C = 1>
class RepeatedReadingDetector {
  static_assert(M == Eigen::Dynamic || (M >= 0 && M <= 32), "the result is a 32-bit channel mask");

 public:
  using Reading = Eigen::Matrix<S, M, C>;

  /// `limit` ≤ 0 disables the detection. M = Eigen::Dynamic: `channels` sizes it (start-up), so
  /// that reset() and update() with readings of that many rows allocate nothing.
  explicit RepeatedReadingDetector(int limit = 0, int channels = M) noexcept(M != Eigen::Dynamic)
      : limit_(limit) {
    if constexpr (M == Eigen::Dynamic) {
      channels = channels < 0 ? 0 : channels;
      last_ = Reading::Zero(channels, C);
      runs_.assign(static_cast<std::size_t>(channels), 0);
    }
    (void)channels;
  }

  /// Starts over from `reading` (no run). Allocates at Eigen::Dynamic only for a reading of
  /// another row count than the last.
  void reset(const Reading& reading) noexcept {
    last_ = reading;
    if constexpr (M == Eigen::Dynamic)
      runs_.assign(static_cast<std::size_t>(reading.rows()), 0);
    else
      runs_.fill(0);
  }

  /// Feeds one sample; returns the mask of channels frozen now (bit k: channel k repeated for more
  /// than `limit` samples in a row).
  std::uint32_t update(const Reading& reading) noexcept {
    // Branch-free: the same instructions whichever channels repeat.
    std::uint32_t frozen = 0;
    const int limit = limit_ > 0 ? limit_ : std::numeric_limits<int>::max();
    for (int k = 0; k < static_cast<int>(runs_.size()); ++k) {
      int same = 1;
      for (int c = 0; c < C; ++c)
        same &= static_cast<int>(reading(k, c) == last_(k, c));
      runs_[k] = (runs_[k] + 1) * same;
      frozen |= static_cast<std::uint32_t>(runs_[k] > limit) << k;
    }
    last_ = reading;
    return frozen;
  }

 private:
  int limit_;
  Reading last_ = Reading::Zero(M == Eigen::Dynamic ? 0 : M, C);
  ChannelArray<int, M> runs_{};
};

}  // namespace tpf
