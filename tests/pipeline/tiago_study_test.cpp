// The TIAGo study on the shipped log (MEASURED, data/real/tiago), held out by time: its split,
// motion events, residuals and Table I.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "offline/pipeline/tiago_study.hpp"
#include "support/temp_dir.hpp"

namespace tpf::offline {
namespace {

TEST(TiagoStudy, Explore) {
  test::TempDir dir("tiago_study");
  TiagoOptions o;
  o.out = dir.path();
  if (getenv("MASK")) o.masked_inputs = {0};
  if (getenv("EPOCHS")) o.training_epochs = atoi(getenv("EPOCHS"));
  const TiagoResult r = run_tiago_study(o, [](const std::string& s) { std::printf("%s\n", s.c_str()); });
  std::printf("split %g %g %g rows %ld %ld trained %ld gate %ld seconds %g\n", r.t_begin, r.t_split, r.t_end,
              (long)r.rows_fit, (long)r.rows_held_out, (long)r.rows_trained, (long)r.rows_gate, r.seconds);
  for (std::size_t j = 0; j < r.events.size(); ++j)
    std::printf("joint %zu starts %d/%d rev %d/%d  res id %.2f nom %.2f comp %.2f mA noise %.2f\n", j + 1,
                r.events[j].fit.starts, r.events[j].held_out.starts, r.events[j].fit.reversals,
                r.events[j].held_out.reversals, r.residual[j].identified_ma, r.residual[j].nominal_ma,
                r.residual[j].compensated_ma, r.noise_ma[j]);
  for (const TiagoGoal& g : r.goals)
    std::printf("joint %d %s nominal %.2f comp %.2f change %.1f target %.0f rows %zu %s\n", g.joint + 1,
                std::string(regime_name(g.regime)).c_str(), g.nominal, g.compensated, g.change, g.target,
                g.rows, g.met ? "met" : "missed");
  for (const auto& s : r.gate) std::printf("gate %s\n", s.c_str());
  for (const auto& s : r.diagnosis_findings) std::printf("finding %s\n", s.c_str());
  for (const auto& s : r.log_problems) std::printf("problem %s\n", s.c_str());
  for (int j : r.compensated_joints) std::printf("kept %d\n", j);
  for (std::size_t j = 0; j < r.residual.size(); ++j) std::printf("gated %zu %.2f\n", j + 1, r.residual[j].gated_ma);
  std::printf("rows trained %ld gate %ld\n", (long)r.rows_trained, (long)r.rows_gate);
}

}  // namespace
}  // namespace tpf::offline
