// The demo's Table I (SIMULATED) at the demo's own scale against the rows README.md states: the
// static and static-to-kinetic RMSE, nominal and with the compensator, within 2 % of the README's
// figures in the Release build (4 % in others, below). The rows are read from README.md, so the
// README and the tree cannot drift apart.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "offline/pipeline/demo_pipeline.hpp"
#include "support/temp_dir.hpp"

namespace tpf::offline {
namespace {

struct StatedRow {
  double nominal = 0, compensated = 0;
};

// The first README row "| <state> | nominal | compensated | …": Table I of `tpf demo`.
StatedRow readme_row(const std::string& state) {
  std::ifstream in(std::filesystem::path(TPF_TEST_DATA_DIR).parent_path() / "README.md");
  std::string line;
  const std::string head = "| " + state + " |";
  while (std::getline(in, line)) {
    if (line.rfind(head, 0) != 0) continue;
    std::istringstream cells(line.substr(head.size()));
    StatedRow row;
    char bar = 0;
    cells >> row.nominal >> bar >> row.compensated;
    if (!cells || bar != '|') ADD_FAILURE() << "README row not read: " << line;
    return row;
  }
  ADD_FAILURE() << "README.md has no row starting with " << head;
  return {};
}

// The README's figures are those of the Release build (GCC -O3). The compensator's training
// follows the last bits of the residual it learns from, and another compiler or optimisation
// level rounds them differently: clang -O1 (the sanitized build) put the static-to-kinetic
// figure with the compensator 2.8 % from GCC's when measured. There the tolerance is 4 %, twice
// that spread; in the Release GCC build it is 2 %.
#if defined(NDEBUG) && defined(__GNUC__) && !defined(__clang__)
constexpr double kTolerance = 0.02;
#else
constexpr double kTolerance = 0.04;
#endif

TEST(DemoTable, StaticAndStaticToKineticAsTheReadmeStates) {
  const test::TempDir dir("demo_table");
  DemoOptions o;  // the demo's scale: logs, seeds, epochs
  o.out = dir.path();
  o.run_measured = false;
  o.run_contacts = false;     // Table I needs the training, calibration and held-out logs only
  o.training_safety_s = 0.0;  // no wall-clock limit: the figures must not depend on the load
  o.run_tiago = false;
  const DemoResult r = run_demo(o);
  for (const ResidualRow& row : r.evaluation.table)  // the moving state too (not pinned)
    if (row.joint == -1 && row.regime == Regime::Moving)
      std::printf("[ figure ] moving: nominal %.2f, with the compensator %.2f mA\n",
                  row.nominal.rmse, row.compensated.rmse);
  for (const auto& [regime, name] : {std::pair{Regime::Static, "static"},
                                     std::pair{Regime::StaticToKinetic, "static-to-kinetic"}}) {
    const StatedRow stated = readme_row(name);
    bool found = false;
    for (const ResidualRow& row : r.evaluation.table) {
      if (row.joint != -1 || row.regime != regime) continue;
      found = true;
      std::printf(
          "[ figure ] %s: nominal %.2f (README %.1f), with the compensator %.2f (README "
          "%.1f) mA\n",
          name, row.nominal.rmse, stated.nominal, row.compensated.rmse, stated.compensated);
      EXPECT_NEAR(row.nominal.rmse, stated.nominal, kTolerance * stated.nominal)
          << name << " nominal";
      EXPECT_NEAR(row.compensated.rmse, stated.compensated, kTolerance * stated.compensated)
          << name << " with the compensator";
    }
    EXPECT_TRUE(found) << name;
  }
}

}  // namespace
}  // namespace tpf::offline
