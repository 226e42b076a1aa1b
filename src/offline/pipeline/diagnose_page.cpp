#include "offline/pipeline/diagnose_page.hpp"

#include "offline/report/text_format.hpp"

namespace tpf::offline {

template <int N>
HtmlReport diagnose_page(const Diagnosis<N>& d, bool simulated) {
  HtmlReport page("tpf diagnose: what the declared model misses");
  if (simulated) page.mark_simulated();
  page.subtitle("log: " + d.samples.source);
  page.heading("Findings");
  page.list(d.findings);
  if (!d.notes.empty()) page.list(d.notes);

  page.heading("Held-out residual before and after the added effects");
  Table t;
  t.header = {"joint", "state", "RMSE before", "RMSE after", "change", "std before", "std after"};
  t.caption = "Effort unit " + d.samples.effort_unit + "; held-out blocks of the log.";
  t.percent_column = 4;
  const char* states[] = {"static", "static-to-kinetic", "moving", "all"};
  for (std::size_t j = 0; j < d.before.size() && j < d.after.size(); ++j) {
    for (int r = 0; r < 4; ++r) {
      const ResidualSums& a = d.before[j][static_cast<std::size_t>(r)];
      const ResidualSums& b = d.after[j][static_cast<std::size_t>(r)];
      t.rows.push_back({std::to_string(j + 1), states[r], format_number(a.rmse()),
                        format_number(b.rmse()), format_percent_change(a.rmse(), b.rmse()),
                        format_number(a.std()), format_number(b.std())});
    }
  }
  page.table(t);

  page.heading("Candidate effects tried");
  Table c;
  c.header = {"round", "candidate", "held-out SSE removed", "ΔBIC", "selected"};
  for (const CandidateTrial& trial : d.trials)
    c.rows.push_back({std::to_string(trial.round), trial.title,
                      format_fixed(100.0 * trial.improvement, 1) + " %",
                      format_number(trial.bic_change), trial.selected ? "yes" : ""});
  page.table(c);
  return page;
}

template HtmlReport diagnose_page<4>(const Diagnosis<4>&, bool);

}  // namespace tpf::offline
