// Several log files read as one log: each file its own segment in time, Log::file_starts filled.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/log/read_log.hpp"

namespace tpf::offline {

/// Seconds of empty time put between two files of a several-file log (at least 100 median
/// sample steps): far more than the gap rule's 1.5 steps, so every tool sees a gap there and no
/// filter, derivative or regime window runs across the seam.
double file_seam_seconds(double median_step_s);

/// Reads each file with read_log and concatenates them in time:
/// - one file: exactly read_log's result (file_starts {0});
/// - columns: those every file has, in the first file's order (a column some file lacks is
///   dropped, and said in `notes`);
/// - time: file k + 1 starts file_seam_seconds after the last sample of file k (its own steps
///   unchanged); Log::file_starts holds the first row of each file; the seams count as gaps in
///   `quality` (quality.seams of them);
/// - metadata: the first file's, 'rate_hz' kept only when every file gives the same one, and
///   'files' listing the paths; source = the paths joined by " + ".
/// - the reader's notes on each file (a cut last row skipped, a contradicted rate_hz): moved to
///   `notes` when given, so that the caller says them once; else kept in quality.notes;
/// Throws read_log's errors (naming the file) and tpf::Error when no path is given or no column
/// is common to all files.
/// `keep_column`: read_log's, for every file (all columns when empty).
Log read_logs(const std::vector<std::filesystem::path>& paths,
              std::vector<std::string>* notes = nullptr, const ColumnFilter& keep_column = {});

/// read_logs of paths given as strings (the command line's --log values).
Log read_logs(const std::vector<std::string>& paths, std::vector<std::string>* notes = nullptr,
              const ColumnFilter& keep_column = {});

}  // namespace tpf::offline
