// A one-line terminal progress bar for long offline jobs.
#pragma once

#include <iosfwd>
#include <string>
#include <string_view>

namespace tpf::offline {

/// Redraws "\r[#######.......]  42%  <status>  ETA 1m05s" on `out` at each update; with
/// `redraw` false (a file or a pipe, where "\r" only piles up) each update is a line of its own.
class TerminalProgressBar {
 public:
  explicit TerminalProgressBar(std::ostream& out, int width = 30, bool redraw = true);

  /// fraction in [0, 1] (clamped); remaining_seconds < 0 prints no ETA.
  void update(double fraction, std::string_view status, double remaining_seconds);
  /// Ends the line.
  void finish();

 private:
  std::ostream& out_;
  int width_;
  bool redraw_;
};

/// "1h02m", "3m05s" or "12s".
std::string format_duration(double seconds);

}  // namespace tpf::offline
