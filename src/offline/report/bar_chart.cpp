#include "offline/report/bar_chart.hpp"

#include <cmath>
#include <limits>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/report/text_format.hpp"
#include "tpf/common/error.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {
namespace {

/// `value` with 3 significant digits, or 2 when that is too wide for a bar `bar` px wide (≈ 6 px
/// a character of the 11 px labels), so that neighbours' labels never run into each other.
std::string bar_label(double value, double bar) {
  const std::string three = format_number(value, 3);
  std::size_t characters = 0;
  for (const char c : three)
    characters += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return 6.0 * static_cast<double>(characters) <= bar ? three : format_number(value, 2);
}

}  // namespace

std::string bar_chart(const PlotOptions& options, const std::vector<std::string>& groups,
                      const std::vector<BarSeries>& series) {
  double lo = 0.0, hi = 0.0;
  for (const BarSeries& s : series) {
    if (s.values.size() != groups.size())
      throw Error("bar series '" + s.name + "': " + std::to_string(s.values.size()) +
                  " values for " + std::to_string(groups.size()) + " groups");
    for (const double v : s.values)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  PlotOptions with_zero = options;
  with_zero.y_include_zero = true;
  PlotCanvas canvas(with_zero, 0.0, 1.0, lo, hi == lo ? lo + 1.0 : hi * 1.08);
  canvas.set_categories(groups);
  const double slot = canvas.x()(1.0) - canvas.x()(0.0);
  const double bar = 0.8 * slot / static_cast<double>(std::max<std::size_t>(series.size(), 1));
  const bool labels = groups.size() * series.size() <= 24;
  std::vector<std::pair<std::string, std::string>> legend;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const std::string colour = series[i].colour.empty() ? series_colour(i) : series[i].colour;
    std::string bars = "<g class=\"bars\" fill=\"" + colour + "\">";
    std::string texts;
    for (std::size_t g = 0; g < groups.size(); ++g) {
      const double v = series[i].values[g];
      if (!std::isfinite(v)) continue;
      const double left =
          canvas.x()(static_cast<double>(g)) + 0.1 * slot + bar * static_cast<double>(i);
      const double top = canvas.y()(std::max(v, 0.0)), bottom = canvas.y()(std::min(v, 0.0));
      bars += "<rect x=\"" + svg_coordinate(left + 1) + "\" y=\"" + svg_coordinate(top) +
              "\" width=\"" + svg_coordinate(bar - 2) + "\" height=\"" +
              svg_coordinate(std::max(bottom - top, 0.5)) + "\"><title>" +
              html_escape(series[i].name + " · " + groups[g] + ": ") + format_number(v) +
              "</title></rect>";
      if (labels)
        texts += "<text class=\"bar-value\" text-anchor=\"middle\" x=\"" +
                 svg_coordinate(left + 0.5 * bar) + "\" y=\"" +
                 svg_coordinate(v >= 0 ? top - 4 : bottom + 12) + "\">" + bar_label(v, bar) +
                 "</text>";
    }
    canvas.add(bars + "</g>\n" + texts + "\n");
    if (!series[i].name.empty()) legend.emplace_back(series[i].name, colour);
  }
  canvas.set_legend(legend);
  return canvas.svg();
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
