// The C++ side of the Python estimator's test (test_estimate.py): the replay estimator of the
// offline tools over a log, every per-row quantity written with 17 significant digits.
//   tpf_python_replay_reference PARAMS ROBOT ESTIMATOR WEIGHTS LOG OUT.csv   (WEIGHTS "": none)
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

#include "offline/log/read_log.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "tpf/estimation/load_estimator.hpp"

namespace {

void write_trace(const tpf::offline::EstimatorTrace& tr, const std::string& path) {
  using tpf::TorqueEstimator;
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error(path + ": cannot write");
  const Eigen::Index n = tr.residual.cols();
  const auto& fixed = tr.estimates[static_cast<int>(TorqueEstimator::StaticModelFree)];
  const auto& fused = tr.estimates[static_cast<int>(TorqueEstimator::Fused)];
  for (Eigen::Index r = 0; r < tr.rows(); ++r) {
    std::fprintf(f, "%.17g,%d,%d", tr.t[r], tr.state[r], tr.estimator_contact[r]);
    for (const Eigen::MatrixXd* m : {&tr.residual, &tr.compensation, &fixed, &fused, &tr.external})
      for (Eigen::Index j = 0; j < n; ++j)
        std::fprintf(f, ",%.17g", (*m)(r, j));
    std::fprintf(f, "\n");
  }
  std::fclose(f);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr, "usage: %s PARAMS ROBOT ESTIMATOR WEIGHTS LOG OUT.csv\n", argv[0]);
    return 2;
  }
  try {
    const tpf::offline::ReplaySetup setup =
        tpf::load_estimator_setup(tpf::EstimatorFiles{argv[1], argv[2], "", argv[3], argv[4]});
    const tpf::offline::Log log = tpf::offline::read_log(argv[5]);
    write_trace(tpf::offline::replay_estimator(
                    setup, tpf::offline::estimator_samples(log, setup.nominal.model, 0)),
                argv[6]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
