// Fuzz target: any bytes as a log file → read_log. Contract: a Log or a one-line tpf::Error naming
// the file; a Log read back is self-consistent (t strictly increasing, no infinity, missing counts
// equal to the NaNs) and survives write_log → read_log unchanged.
#include <cmath>

#include "fuzz_support.hpp"
#include "offline/log/log_io.hpp"

namespace {

void check_log(const tpf::offline::Log& log) {
  using tpf::fuzz::violation;
  if (log.values.cols() != static_cast<Eigen::Index>(log.columns.size()))
    violation("read_log", "column count differs from the matrix width");
  if (log.values.array().isInf().any()) violation("read_log", "an infinite value was accepted");
  const auto t = log.col("t");
  for (Eigen::Index r = 0; r < t.size(); ++r) {
    if (std::isnan(t[r])) violation("read_log", "a missing t was accepted");
    if (r > 0 && !(t[r] > t[r - 1])) violation("read_log", "t does not increase");
  }
  if (log.quality.missing_per_column.size() == log.columns.size())
    for (std::size_t c = 0; c < log.columns.size(); ++c)
      if (log.quality.missing_per_column[c] !=
          static_cast<std::size_t>(
              log.values.col(static_cast<Eigen::Index>(c)).array().isNaN().count()))
        violation("read_log", "missing count differs from the NaNs in column " + log.columns[c]);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = tpf::fuzz::write_input({data, size}, "input.csv");
  tpf::fuzz::expect_clean_error(path.string(), [&] {
    const tpf::offline::Log log = tpf::offline::read_log(path);
    check_log(log);
    // Round trip: what was read is written and read back bit for bit (NaN stays NaN).
    const auto copy_path = tpf::fuzz::scratch_dir() / "copy.csv";
    try {
      tpf::offline::write_log(copy_path, log);
    } catch (const tpf::Error&) {
      return;  // names the writer cannot hold (e.g. metadata keys with line breaks) are refused
    }
    const tpf::offline::Log copy = tpf::offline::read_log(copy_path);
    if (copy.columns != log.columns) tpf::fuzz::violation("round trip", "columns differ");
    if (copy.values.rows() != log.values.rows() ||
        !((copy.values.array() == log.values.array()) ||
          (copy.values.array().isNaN() && log.values.array().isNaN()))
             .all())
      tpf::fuzz::violation("round trip", "values differ");
  });
  return 0;
}
