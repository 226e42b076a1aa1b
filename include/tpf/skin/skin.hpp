// The skin at run time: P pads, each with its geometry, contact detector and normal-force reading.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "tpf/common/error.hpp"
#include "tpf/kinematics/contact_frame.hpp"
#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/skin/pad_contact_detector.hpp"
#include "tpf/skin/pad_layout.hpp"

namespace tpf {

/// A pad's fixed geometry in scalar S: link index (1..N), centre and unit outward normal in the
/// link frame [m], area [m²], and its contact frame's axes in the link frame
/// (contact_frame_in_link(normal), computed once).
template <typename S>
struct PadGeometry {
  int link = 0;
  Vector3<S> center = Vector3<S>::Zero();
  Vector3<S> normal = Vector3<S>::UnitZ();
  S area = S(0);
  Matrix3<S> contact_frame = Matrix3<S>::Identity();
};

/// Skin settings: the detector of every pad, and the pressure-to-force gain of the normal-force
/// reading F_n = gain·p·A [N] (p in kPa → ·1000 Pa, A the pad area in m²). The gain is < 1 when
/// the contact covers only part of the pad; it is rough by nature (it depends on the contact area).
template <typename S>
struct SkinSettings {
  PadDetectorSettings<S> detector;
  S force_gain = S(1);
  /// The pressure sensors' range end [kPa] (0–5 psi sensors): a reading there is saturated, a
  /// hard push, not a stuck sensor.
  S full_scale_kpa = S(34.474);
};

/// Pads 0..P−1 (the pad layout file's order; log column p<k> is pad k−1). P = 0: no skin;
/// P = Eigen::Dynamic: the layout's count, up to 32 (the offline tools).
template <typename S, int P>
class Skin {
  static_assert(P == Eigen::Dynamic || (P >= 0 && P <= 32), "pad masks are 32 bits wide");

 public:
  using Pressures = Eigen::Matrix<S, P, 1>;

  Skin() = default;

  /// From a loaded pad layout (start-up: throws tpf::Error when the layout does not have P pads
  /// or names a link outside 1..N).
  Skin(const std::vector<Pad>& layout, const SkinSettings<S>& settings, int joints,
       const std::string& source = "pad layout")
      : settings_(settings) {
    if constexpr (P == Eigen::Dynamic) {
      if (layout.size() > 32)
        throw Error::at(source, 0, "pads",
                        "the layout has " + std::to_string(layout.size()) +
                            " pads; at most 32 are supported (32-bit pad masks)");
      geometry_.resize(layout.size());
      detectors_.resize(layout.size());
    } else if (static_cast<int>(layout.size()) != P) {
      throw Error::at(source, 0, "pads",
                      "the layout has " + std::to_string(layout.size()) +
                          " pads, this program is built for " + std::to_string(P));
    }
    for (int k = 0; k < count(); ++k) {
      const Pad& pad = layout[k];
      if (pad.link < 1 || pad.link > joints)
        throw Error::at(source, 0, pad.name, "link index outside 1.." + std::to_string(joints));
      const Vector3<S> normal = pad.normal.normalized().cast<S>();
      geometry_[k] = {pad.link, pad.center.cast<S>(), normal, S(pad.area),
                      contact_frame_in_link(normal)};
      detectors_[k] = PadContactDetector<S>(settings.detector);
    }
  }

  /// Starts every detector from pressures p at time t (no contact, offsets = p).
  void reset(S t, const Pressures& p) noexcept {
    for (int k = 0; k < count(); ++k)
      detectors_[k].reset(t, p[k]);
  }

  /// Advances every pad whose pressure is finite; pads with NaN/inf keep their state. Returns the
  /// number of pads skipped for non-finite pressure.
  int update(S t, S h, const Pressures& p) noexcept {
    int skipped = 0;
    // Every pad's detector has settings_.detector: one α and one offset gain for all.
    const PadStepFactors<S> factors = PadStepFactors<S>::at(settings_.detector, h);
    for (int k = 0; k < count(); ++k) {
      if (std::isfinite(p[k]))
        detectors_[k].update(t, p[k], factors);
      else
        ++skipped;
    }
    return skipped;
  }

  /// Pads to disbelieve (bit k: pad k), e.g. a pad stuck high: they keep filtering, but
  /// in_contact, any_contact, onset, earliest_new_onset and most_loaded treat them as untouched.
  void set_ignored(std::uint32_t mask) noexcept { ignored_ = mask; }
  std::uint32_t ignored() const noexcept { return ignored_; }
  bool is_ignored(int k) const noexcept { return ignored_ & (std::uint32_t(1) << k); }

  /// Pad k reports contact and is not ignored.
  bool in_contact(int k) const noexcept { return !is_ignored(k) && detectors_[k].in_contact(); }
  bool any_contact() const noexcept {
    for (int k = 0; k < count(); ++k)
      if (in_contact(k)) return true;
    return false;
  }
  /// Number of pads in contact (ignored pads excluded).
  int contact_count() const noexcept {
    int n = 0;
    for (int k = 0; k < count(); ++k)
      n += in_contact(k) ? 1 : 0;
    return n;
  }
  /// True when pad k switched on at the last update.
  bool onset(int k) const noexcept { return detectors_[k].changed() && in_contact(k); }
  /// The earliest onset time among pads that switched on at the last update; +inf if none did.
  S earliest_new_onset() const noexcept {
    S t = std::numeric_limits<S>::infinity();
    for (int k = 0; k < count(); ++k)
      if (onset(k) && detectors_[k].onset_time() < t) t = detectors_[k].onset_time();
    return t;
  }
  /// The earliest onset time among pads in contact (ignored pads excluded); +inf if none is.
  S earliest_onset() const noexcept {
    S t = std::numeric_limits<S>::infinity();
    for (int k = 0; k < count(); ++k)
      if (in_contact(k) && detectors_[k].onset_time() < t) t = detectors_[k].onset_time();
    return t;
  }
  /// The pad in contact with the largest load, or −1 when none is.
  int most_loaded() const noexcept {
    int best = -1;
    for (int k = 0; k < count(); ++k)
      if (in_contact(k) && (best < 0 || load_kpa(k) > load_kpa(best))) best = k;
    return best;
  }
  S load_kpa(int k) const noexcept { return detectors_[k].load_kpa(); }
  /// Normal force reading of pad k, F_n = gain·max(load, 0)·1000·A [N] (≥ 0, a push).
  S normal_force(int k) const noexcept {
    using std::max;
    return settings_.force_gain * max(load_kpa(k), S(0)) * S(1000) * geometry_[k].area;
  }
  /// Number of pads (P, or the layout's count when P is Eigen::Dynamic).
  int count() const noexcept { return static_cast<int>(geometry_.size()); }
  const PadContactDetector<S>& detector(int k) const noexcept { return detectors_[k]; }
  const PadGeometry<S>& geometry(int k) const noexcept { return geometry_[k]; }
  const SkinSettings<S>& settings() const noexcept { return settings_; }

 private:
  SkinSettings<S> settings_;
  ChannelArray<PadGeometry<S>, P> geometry_{};
  ChannelArray<PadContactDetector<S>, P> detectors_{};
  std::uint32_t ignored_ = 0;
};

/// Contact point p = oMi[link]·c [m] of a pad, world frame. Needs forward_kinematics first.
template <typename S, int N>
Vector3<S> pad_point_in_world(const Data<S, N>& data, const PadGeometry<S>& pad) {
  return world_point(data, pad.link, pad.center);
}

/// The pad's contact frame in world coordinates (z = outward normal, see contact_frame_in_link):
/// oMi[link].R·contact_frame. Needs forward_kinematics first.
template <typename S, int N>
Matrix3<S> pad_contact_frame_in_world(const Data<S, N>& data, const PadGeometry<S>& pad) {
  return data.oMi[pad.link].R * pad.contact_frame;
}

/// Outward normal n_world = oMi[link].R·n of a pad, world frame. Needs forward_kinematics first.
template <typename S, int N>
Vector3<S> pad_normal_in_world(const Data<S, N>& data, const PadGeometry<S>& pad) {
  return data.oMi[pad.link].R * pad.normal;
}

}  // namespace tpf
