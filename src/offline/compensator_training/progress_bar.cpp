#include "offline/compensator_training/progress_bar.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

namespace tpf::offline {

TerminalProgressBar::TerminalProgressBar(std::ostream& out, int width, bool redraw)
    : out_(out), width_(std::max(width, 1)), redraw_(redraw) {}

void TerminalProgressBar::update(double fraction, std::string_view status,
                                 double remaining_seconds) {
  fraction = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
  const int filled = static_cast<int>(std::lround(fraction * width_));
  out_ << (redraw_ ? "\r[" : "[") << std::string(filled, '#') << std::string(width_ - filled, '.')
       << "] ";
  char percent[8];
  std::snprintf(percent, sizeof percent, "%3d%%", static_cast<int>(std::lround(100 * fraction)));
  out_ << percent << "  " << status;
  if (remaining_seconds >= 0.0) out_ << "  ETA " << format_duration(remaining_seconds);
  out_ << (redraw_ ? "   " : "\n") << std::flush;
}

void TerminalProgressBar::finish() {
  if (redraw_) out_ << '\n' << std::flush;
}

std::string format_duration(double seconds) {
  const long s = std::lround(std::max(seconds, 0.0));
  char text[32];
  if (s >= 3600) {
    std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, (s / 60) % 60);
  } else if (s >= 60) {
    std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%lds", s);
  }
  return text;
}

}  // namespace tpf::offline
