// A robot model with its workspace, for Python: the core at Eigen::Dynamic.
#pragma once

#include <Eigen/Core>
#include <utility>

#include "arrays.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/model.hpp"

namespace tpf::python {

/// Model, Data and three joint vectors the samples are copied into (the core takes whole
/// vectors; copying into these allocates nothing). Python calls on one Robot hold the GIL, so
/// they never share the workspace at once.
struct Robot {
  Model<double, Eigen::Dynamic> model;
  Data<double, Eigen::Dynamic> data;
  Eigen::VectorXd a, b, c;

  explicit Robot(Model<double, Eigen::Dynamic> m)
      : model(std::move(m)), data(model), a(n()), b(n()), c(n()) {}
  int n() const { return model.joint_count(); }
};

}  // namespace tpf::python
