#include "arm/estimator_hook.hpp"

namespace tpf::arm {

void run_estimator_hook(const CycleSample& sample) noexcept {
  // The core Estimator is not part of tpf yet; this is its call site.
  static_cast<void>(sample);
}

}  // namespace tpf::arm
