// The three states of the contact-aware state machine (docs/design.md).
#pragma once

#include <cstdint>
#include <string_view>

namespace tpf {

/// (i) every joint static, no pad in contact; (ii) every joint static, a pad in contact;
/// (iii) at least one joint moving. "Static" is |q̇_j| < StaticFrictionSettings::static_velocity
/// (with a coupled transmission: every motor acting on the joint, |(C·q̇)_m| below it).
enum class ContactState : std::uint8_t { StaticFree, StaticContact, Dynamic };

/// "static-free", "static-contact", "dynamic".
constexpr std::string_view contact_state_name(ContactState s) noexcept {
  switch (s) {
    case ContactState::StaticFree:
      return "static-free";
    case ContactState::StaticContact:
      return "static-contact";
    case ContactState::Dynamic:
      return "dynamic";
  }
  return "?";
}

}  // namespace tpf
