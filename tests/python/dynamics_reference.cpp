// The C++ side of the Python dynamics' test (test_dynamics.py): for every state of a CSV file
// (q, q̇, q̈ of n joints per row), the core's RNEA, gravity, mass matrix (row-major) and forward
// dynamics under the RNEA's torque, written with 17 significant digits, one row per state.
//   tpf_python_dynamics_reference ROBOT STATES.csv OUT.csv
#include <cstdio>
#include <exception>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tpf/dynamics/forward_dynamics.hpp"
#include "tpf/dynamics/mass_matrix.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/model/load_robot.hpp"

namespace {

std::vector<std::vector<double>> read_rows(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<double> row;
    std::stringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');)
      row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

void write_values(std::FILE* f, const double* values, Eigen::Index count) {
  for (Eigen::Index k = 0; k < count; ++k)
    std::fprintf(f, ",%.17g", values[k]);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s ROBOT STATES.csv OUT.csv\n", argv[0]);
    return 2;
  }
  try {
    const auto model = tpf::load_robot<double, Eigen::Dynamic>(argv[1]);
    tpf::Data<double, Eigen::Dynamic> data(model);
    const int n = model.joint_count();
    std::FILE* out = std::fopen(argv[3], "w");
    if (!out) throw std::runtime_error(std::string(argv[3]) + ": cannot write");
    for (const std::vector<double>& row : read_rows(argv[2])) {
      if (row.size() != static_cast<std::size_t>(3 * n))
        throw std::runtime_error("a state row holds 3n values");
      const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(row.data(), n),
                            dq = Eigen::Map<const Eigen::VectorXd>(row.data() + n, n),
                            ddq = Eigen::Map<const Eigen::VectorXd>(row.data() + 2 * n, n);
      const Eigen::VectorXd tau = tpf::rnea(model, data, q, dq, ddq);
      const Eigen::VectorXd gravity = tpf::compute_gravity(model, data, q);
      const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> M =
          tpf::compute_mass_matrix(model, data, q);
      const Eigen::VectorXd acceleration = tpf::forward_dynamics(model, data, q, dq, tau);
      std::fprintf(out, "%d", n);
      write_values(out, tau.data(), n);
      write_values(out, gravity.data(), n);
      write_values(out, M.data(), M.size());
      write_values(out, acceleration.data(), n);
      std::fprintf(out, "\n");
    }
    std::fclose(out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
