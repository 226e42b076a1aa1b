// The registration of the effects `tpf diagnose` may add to the declared model: the memoryless
// ones the run time evaluates (one typed object each, see its header), and the ones a parameter
// file must not hold. Adding an effect = one header like joint_spring.hpp + one entry below.
#pragma once

#include <tuple>
#include <utility>

#include "tpf/effects/effect_input.hpp"
#include "tpf/effects/effort_delay.hpp"
#include "tpf/effects/joint_offset.hpp"
#include "tpf/effects/joint_spring.hpp"
#include "tpf/effects/motion_coupling.hpp"
#include "tpf/effects/position_ripple.hpp"
#include "tpf/effects/thermal_friction.hpp"

namespace tpf {

/// Evaluated at run time, in this order. Each type has a `key`, its parameters (zero = absent),
/// resize(n) (n joints, absent), assign(other joint-count type), columns() (basis functions per
/// joint), present() (some parameter is in use: without one, add_torque adds nothing),
/// add_torque(EffectInput, τ) (allocation-free, noexcept) and read(Fields&) / write(Json&) of its
/// fields of the parameter file's "added_effects".
template <typename S, int N>
using RunTimeEffects =
    std::tuple<JointSpring<S, N>, JointOffset<S, N>, MotionCoupling<S, N>, PositionRipple<S, N>>;

/// Found by diagnosis but not evaluated at run time: each has a `key` and refuse(Fields&, joints),
/// which refuses a parameter file holding the effect.
using OfflineOnlyEffects = std::tuple<ThermalFriction, EffortDelay>;

/// The added effects of a nominal model: one object of each RunTimeEffects type.
template <typename S, int N>
struct AddedEffects {
  RunTimeEffects<S, N> effects;

  /// Sizes every effect for n joints, all absent (needed at Eigen::Dynamic before reading).
  void resize(int n) {
    for_each([n](auto& effect) { effect.resize(n); });
  }
  /// The effects of another joint-count type (the counts must agree).
  template <int From>
  void assign(const AddedEffects<S, From>& from) {
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      (std::get<I>(effects).assign(std::get<I>(from.effects)), ...);
    }
    (std::make_index_sequence<std::tuple_size_v<RunTimeEffects<S, N>>>{});
  }

  /// The effect of type Effect, e.g. added.get<JointSpring>().stiffness.
  template <template <typename, int> class Effect>
  Effect<S, N>& get() noexcept {
    return std::get<Effect<S, N>>(effects);
  }
  template <template <typename, int> class Effect>
  const Effect<S, N>& get() const noexcept {
    return std::get<Effect<S, N>>(effects);
  }
  /// Calls f(effect) for each effect, in registration order.
  template <typename F>
  void for_each(F&& f) {
    std::apply([&f](auto&... effect) { (f(effect), ...); }, effects);
  }
  template <typename F>
  void for_each(F&& f) const {
    std::apply([&f](const auto&... effect) { (f(effect), ...); }, effects);
  }
  /// Some effect is present (without one, torque() is all zeros).
  bool any() const noexcept {
    bool present = false;
    for_each([&present](const auto& effect) { present = present || effect.present(); });
    return present;
  }
  /// Σ of every effect's torque [N·m]. Allocation-free at a fixed joint count.
  JointVector<S, N> torque(const EffectInput<S, N>& x) const noexcept(N != Eigen::Dynamic) {
    JointVector<S, N> tau = JointVector<S, N>::Zero(x.q.size());
    for_each([&](const auto& effect) { effect.add_torque(x, tau); });
    return tau;
  }
};

/// Calls f.template operator()<Effect>() for each OfflineOnlyEffects type.
template <typename F>
void for_each_offline_only_effect(F&& f) {
  [&f]<typename... Effect>(std::tuple<Effect...>*) {
    (f.template operator()<Effect>(), ...);
  }(static_cast<OfflineOnlyEffects*>(nullptr));
}

}  // namespace tpf
