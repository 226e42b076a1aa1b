// What decides which column families a design offers, and how they are named.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "offline/effects/candidate_inputs.hpp"

namespace tpf::offline {

struct DesignContext {
  int joints = 0;
  const std::vector<int>& base_columns;  ///< regressor columns of the base parameters
  const CandidateInputs& inputs;
  bool has_temperature = false;  ///< the samples hold temp<j> of every joint
  bool coupled = false;          ///< the model's motors are coupled (Model::coupled)
};

/// A family as an effect type offers it for one joint (or every joint); the design adds its key,
/// joint, written_to and columns.
struct GroupSpec {
  GroupSpec(std::string title, std::vector<std::string> column_names, int held_column = -1,
            std::vector<std::string> judged_beside = {})
      : title(std::move(title)),
        column_names(std::move(column_names)),
        held_column(held_column),
        judged_beside(std::move(judged_beside)) {}

  std::string title;
  std::vector<std::string> column_names;
  int held_column;  ///< index in column_names of the friction held at rest, −1 = none
  std::vector<std::string> judged_beside;
  bool indistinct_from_beside = false;  ///< FeatureGroup::indistinct_from_beside
  std::vector<int> joints;              ///< FeatureGroup::joints
  std::vector<int> dissipative;         ///< FeatureGroup::dissipative
};

/// "joint 3" of 0-based joint 2.
inline std::string joint_title(int joint) {
  return "joint " + std::to_string(joint + 1);
}
/// "3" of 0-based joint 2: the suffix of a column name.
inline std::string joint_suffix(int joint) {
  return std::to_string(joint + 1);
}

}  // namespace tpf::offline
