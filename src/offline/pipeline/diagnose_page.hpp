// A readable page of a diagnosis (the demo's diagnose stage): what was found, the candidates
// tried, and the held-out residual before and after the effects were added.
#pragma once

#include "offline/diagnose/diagnose.hpp"
#include "offline/report/html_report.hpp"

namespace tpf::offline {

/// The page for `diagnosis` of an N-joint arm; `simulated` adds the SIMULATED banner.
template <int N>
HtmlReport diagnose_page(const Diagnosis<N>& diagnosis, bool simulated);

}  // namespace tpf::offline
