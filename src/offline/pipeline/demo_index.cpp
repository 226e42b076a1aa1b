#include "offline/pipeline/demo_index.hpp"

#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/evaluate/evaluation_report.hpp"
#include "offline/measured_study/measured_report.hpp"
#include "offline/pipeline/tiago_report.hpp"
#include "offline/report/html_report.hpp"
#include "offline/report/text_format.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {
namespace {

/// Width [px] of the figure beside Table I on the first screen.
constexpr int kMeasuredChartWidth = 760;

/// Table I on the twin, pooled over joints (SIMULATED).
std::string table_one_panel(const DemoResult& r) {
  HtmlReport panel("");
  panel.heading("Digital twin (SIMULATED): Table I");
  panel.table(table_one_summary(r.evaluation));
  panel.nav({{"evaluate.html", "Detection, force, dead bands and teaching", ""}});
  return panel.body();
}

std::string measured_panel(const DemoOptions& o, const DemoResult& r) {
  HtmlReport panel("");
  add_measured_headline(panel, *r.measured, o.measured.target_reduction, kMeasuredChartWidth);
  return panel.body();
}

std::string tiago_panel(const DemoOptions& o, const DemoResult& r) {
  HtmlReport panel("");
  add_tiago_headline(panel, *r.tiago, o.tiago);
  return panel.body();
}

std::string diagnosis_panel(const DemoResult& r) {
  HtmlReport panel("");
  panel.heading("Digital twin (SIMULATED): what diagnose adds to the declared model");
  panel.table(r.diagnosis_summary);
  return panel.body();
}

/// The other pages and the JSON files beside them.
std::vector<Link> page_links(const DemoOptions& o, const DemoResult& r) {
  std::vector<Link> links;
  if (o.run_twin) links.push_back({"diagnose.html", "diagnose", ""});
  if (o.run_twin) links.push_back({"evaluate.html", "evaluate", ""});
  if (r.measured) links.push_back({"measured.html", "measured arm", ""});
  if (r.tiago) links.push_back({"tiago.html", "TIAGo", ""});
  if (o.run_twin) links.push_back({"diagnosis.json", "diagnosis.json", ""});
  if (o.run_twin) links.push_back({"evaluation.json", "evaluation.json", ""});
  if (r.measured) links.push_back({"measured.json", "measured.json", ""});
  if (r.tiago) links.push_back({"tiago.json", "tiago.json", ""});
  return links;
}

/// The twin's details, collapsed: diagnose's findings, the headline numbers, the stages.
void add_twin_details(HtmlReport& page, const DemoResult& r) {
  page.open_details("Digital twin: diagnose's findings in full");
  page.list(r.findings);
  page.close_details();
  page.open_details("Digital twin: the evaluation's headline numbers");
  page.preformatted(evaluation_headline(r.evaluation, true));
  page.close_details();
  page.open_details("Digital twin: the stages and logs");
  page.list(r.stages);
  page.close_details();
}

}  // namespace

void write_demo_index(const std::filesystem::path& out, const DemoOptions& o, const DemoResult& r) {
  HtmlReport page("tpf: the whole loop on a digital twin and on a measured arm");
  page.wide();
  const bool measured = r.measured || r.tiago;
  if (measured && o.run_twin)
    page.mark_mixed();
  else if (r.measured && r.tiago)
    page.mark_measured("Kinova Gen3 logs, W. Chiha, MIT licence; TIAGo log, T. Nguyen, Apache-2.0");
  else if (r.measured)
    page.mark_measured("Kinova Gen3 logs, W. Chiha, MIT licence");
  else if (r.tiago)
    page.mark_measured("TIAGo log, T. Nguyen, Apache-2.0");
  else
    page.mark_simulated();
  page.subtitle(std::string(o.run_twin ? "Twin: simulate → identify → diagnose → train → "
                                         "evaluate. "
                                       : "") +
                (r.measured ? "Measured arm: identify → diagnose → train, scored on held-out "
                              "files. "
                            : "") +
                (r.tiago ? "TIAGo: the same, held out by time. " : "") +
                format_number(r.seconds, 3) + " s.");
  page.nav(page_links(o, r));
  std::vector<std::string> first;
  if (o.run_twin) first.push_back(table_one_panel(r));
  if (r.measured) first.push_back(measured_panel(o, r));
  page.panels(first, {5, 6});
  if (r.tiago) page.panels({tiago_panel(o, r)});
  if (o.run_twin) page.panels({diagnosis_panel(r)});
  if (o.run_twin) add_twin_details(page, r);
  if (r.measured) {
    page.open_details("Kinova Gen3: every model against the torque sensor");
    add_measured_summary(page, *r.measured, o.measured.target_reduction);
    page.close_details();
  }
  page.write(out / "index.html");
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
