// Joint vectors and matrices as the plain arrays of a parameter file: what every added effect's
// write() stores (nlohmann::json converts std::vector).
#pragma once

#include <vector>

#include "tpf/common/types.hpp"

namespace tpf {

template <typename S, int N>
std::vector<double> joint_values(const JointVector<S, N>& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

/// One array per row.
template <typename S, int N>
std::vector<std::vector<double>> joint_rows(const JointMatrix<S, N>& m) {
  std::vector<std::vector<double>> rows;
  for (int r = 0; r < m.rows(); ++r)
    rows.push_back(joint_values<S, N>(m.row(r).transpose()));
  return rows;
}

}  // namespace tpf
