// An identified nominal model for Python (tpf.NominalModel), with its link form and workspace.
#pragma once

#include <Eigen/Core>
#include <utility>

#include "arrays.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/model/data.hpp"

namespace tpf::python {

/// The model with its link form and the vectors the samples are copied into.
struct Nominal {
  NominalModelX nominal;
  NominalLinks<double, Eigen::Dynamic> links;
  Data<double, Eigen::Dynamic> data;
  Eigen::VectorXd q, dq, ddq, rigid, friction;

  explicit Nominal(NominalModelX m)
      : nominal(std::move(m)), links(nominal_links(nominal)), data(nominal.model) {}
  int n() const { return nominal.model.joint_count(); }
};

}  // namespace tpf::python
