// The skin: where each pneumatic pad sits on the arm.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "tpf/common/types.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

/// One pad: a contact on it acts at `center` along −`normal` (a push), both in the frame of link
/// `link` (1..N, the link that moves with joint `link`). Area in m².
struct Pad {
  std::string name;
  int link = 0;
  Vector3<double> center = Vector3<double>::Zero();
  Vector3<double> normal = Vector3<double>::UnitZ();  ///< unit, outward.
  double area = 0;
};

/// Reads a pad layout file (JSON, format "tpf-pads" version 1). Links are given by name and
/// resolved against `link_names` ([0] is the base, which carries no pads). Normals are
/// normalised; a zero normal, a non-positive area or an unknown link is refused, naming the pad.
std::vector<Pad> load_pads(const std::filesystem::path& pads_file,
                           const std::vector<std::string>& link_names);

/// load_pads against a model's link names.
template <typename S, int N>
std::vector<Pad> load_pads(const std::filesystem::path& pads_file, const Model<S, N>& model) {
  return load_pads(pads_file,
                   std::vector<std::string>(model.link_names.begin(), model.link_names.end()));
}

}  // namespace tpf
