// The demo's entry page, index.html: its first screen shows the headline as tables and a figure
// (Table I on the twin, the measured arm's error per joint, diagnose's verdict); the rest of the
// summary sits in collapsed sections below, every number in the JSON files beside it.
#pragma once

#include <filesystem>

#include "offline/pipeline/demo_pipeline.hpp"

namespace tpf::offline {

/// Writes out/index.html.
void write_demo_index(const std::filesystem::path& out, const DemoOptions& options,
                      const DemoResult& result);

}  // namespace tpf::offline
