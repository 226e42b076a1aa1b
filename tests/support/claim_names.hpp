// A diagnosis's claims as short names ("ripple@2": key and 1-based joint; 0 = every joint), for
// tests that check what was named and print it.
#pragma once

#include <set>
#include <string>

#include "offline/diagnose/diagnose.hpp"

namespace tpf::test {

/// "key@joint", built piece by piece (a chain of string + string trips GCC 12's -Wrestrict).
inline std::string claim_name(const std::string& key, int joint) {
  std::string name = key;
  name += '@';
  name += std::to_string(joint);
  return name;
}

/// What one claim names: its group's key and joint and, when ambiguous, the alternatives'.
inline std::set<std::string> claim_names(const offline::Diagnosis& d, const offline::Claim& c) {
  std::set<std::string> names;
  for (int g : c.groups)
    names.insert(claim_name(d.groups[g].key, d.groups[g].joint + 1));
  return names;
}

/// Every claim: "named{ripple@2 } ambiguous{offset@1 spring@1 } ", or "nothing".
inline std::string describe_claims(const offline::Diagnosis& d) {
  std::string text;
  for (const offline::Claim& c : d.claims) {
    text += c.ambiguous() ? "ambiguous{" : "named{";
    for (const std::string& n : claim_names(d, c))
      text += n + " ";
    text += "} ";
  }
  return text.empty() ? "nothing" : text;
}

}  // namespace tpf::test
