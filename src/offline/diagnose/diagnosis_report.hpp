// The diagnosis as a page a person reads (HTML via the report kit) and as JSON for scripts.
#pragma once

#include <filesystem>
#include <string>

#include "offline/diagnose/diagnose.hpp"

namespace tpf::offline {

/// The numbers of a diagnosis as JSON text: per joint and regime the held-out RMSE, std and count
/// before and after with the change in percent, the candidate trials, the selected effects, the
/// findings and notes, and "simulated".
std::string diagnosis_json(const EffectDiagnosis& diagnosis);

/// Writes the HTML report (labelled SIMULATED when the log's metadata says so): the verdict per
/// effect (diagnosis_summary_table, judged with `options`) and the per-regime bars first, then
/// in collapsed sections the findings, the before/after table, the evidence table, residual over
/// time before and after, and the residual against each selected effect's term.
void write_diagnosis_report(const EffectDiagnosis& diagnosis, const std::filesystem::path& html,
                            const DiagnoseOptions& options = {});

}  // namespace tpf::offline
