#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <regex>
#include <set>
#include <sstream>

#include "offline/regimes/regime_stats.hpp"
#include "offline/report/bar_chart.hpp"
#include "offline/report/histogram.hpp"
#include "offline/report/html_report.hpp"
#include "offline/report/line_plot.hpp"
#include "offline/report/nice_ticks.hpp"
#include "offline/report/scatter_plot.hpp"
#include "offline/report/text_format.hpp"
#include "tag_checker.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Eigen::VectorXd vec(std::initializer_list<double> values) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index k = 0;
  for (const double x : values)
    v[k++] = x;
  return v;
}

TEST(NiceTicks, StepsAreOneTwoFiveTimesAPowerOfTen) {
  Ticks t = nice_ticks(0.0, 9.3, 5);
  EXPECT_DOUBLE_EQ(t.step, 2.0);
  EXPECT_DOUBLE_EQ(t.lo, 0.0);
  EXPECT_DOUBLE_EQ(t.hi, 10.0);
  EXPECT_EQ(t.values, (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(t.decimals, 0);
  t = nice_ticks(-0.013, 0.047, 5);
  EXPECT_DOUBLE_EQ(t.step, 0.02);  // range 0.06 → nice 0.1 → 0.1 / 5 = 0.02
  EXPECT_NEAR(t.lo, -0.02, 1e-15);
  EXPECT_NEAR(t.hi, 0.06, 1e-15);
  EXPECT_EQ(t.values.size(), 5u);
  EXPECT_EQ(t.values[1], 0.0);  // exact zero
  EXPECT_EQ(t.decimals, 2);
  t = nice_ticks(280.17, 280.17, 5);  // degenerate range is widened
  EXPECT_LT(t.lo, 280.17);
  EXPECT_GT(t.hi, 280.17);
  t = nice_ticks(kNaN, 1.0, 5);
  EXPECT_EQ(t.lo, 0.0);
  EXPECT_EQ(t.hi, 1.0);
  EXPECT_DOUBLE_EQ(nice_number(0.034, true), 0.05);
  EXPECT_DOUBLE_EQ(nice_number(7300, false), 10000);
  EXPECT_DOUBLE_EQ(nice_number(140, true), 100);
}

TEST(TextFormat, EscapingAndNumbers) {
  EXPECT_EQ(html_escape("a<b & c>\"d'"), "a&lt;b &amp; c&gt;&quot;d&#39;");
  EXPECT_EQ(format_number(280.17), "280.2");
  EXPECT_EQ(format_number(-31.96), "\u221231.96");
  EXPECT_EQ(format_number(0.000123, 3), "1.23e\u22124");
  EXPECT_EQ(format_number(1234567.0), "1.235e6");
  EXPECT_EQ(format_number(kNaN), "\u2013");
  EXPECT_EQ(format_fixed(-0.001, 1), "0.0");
  EXPECT_EQ(format_percent_change(280.17, 31.96), "\u221288.6\u00a0%");
  EXPECT_EQ(format_percent_change(100, 150), "+50.0\u00a0%");
  EXPECT_EQ(format_percent_change(0, 1), "\u2013");
}

/// The dots of a scatter plot's series paths ("M x yh0" each), in order.
std::vector<std::pair<double, double>> dots(const std::string& svg) {
  std::vector<std::pair<double, double>> xy;
  const std::regex pattern("M([-0-9.]+) ([-0-9.]+)h0");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), pattern);
       it != std::sregex_iterator(); ++it)
    xy.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
  return xy;
}

TEST(ScatterPlot, DataRangeMapsOntoThePlotArea) {
  PlotOptions options;
  options.width = 500;
  options.height = 300;
  const Series s{"r", vec({-3.0, 7.0, 2.0}), vec({0.0, 10.0, 5.0}), ""};
  const std::string svg = scatter_plot(options, {s});
  const auto xy = dots(svg);
  ASSERT_EQ(xy.size(), 3u);
  // x_min lands on the left axis, x_max on the right edge, the middle in proportion (whole
  // pixels).
  EXPECT_NEAR(xy[0].first, PlotCanvas::kLeft, 0.5);
  EXPECT_NEAR(xy[1].first, 500 - PlotCanvas::kRight, 0.5);
  EXPECT_NEAR(xy[2].first, PlotCanvas::kLeft + 0.5 * (500 - PlotCanvas::kLeft - PlotCanvas::kRight),
              0.5);
  // y: 0 and 10 are nice ticks, so they land on the bottom and top of the plot area.
  EXPECT_NEAR(xy[0].second, 300 - PlotCanvas::kBottom, 0.5);
  EXPECT_NEAR(xy[1].second, PlotCanvas::kTop, 0.5);
  EXPECT_NEAR(xy[2].second, 0.5 * (PlotCanvas::kTop + 300 - PlotCanvas::kBottom), 0.5);
  EXPECT_TRUE(test::check_tags(svg).empty()) << test::check_tags(svg);
}

TEST(ScatterPlot, KeepsOneDotPerSeriesInEachThreePixelCell) {
  PlotOptions options;
  options.width = 500;
  options.height = 300;
  // 200 000 samples on a sine: the dots left are about the cells the curve crosses, a few per
  // pixel column, and every cell the curve crosses keeps one (its top and bottom too).
  const Eigen::Index n = 200000;
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
  const Eigen::VectorXd y = (2 * std::numbers::pi * x).array().sin();
  const std::string svg = scatter_plot(options, {{"sine", x, y, ""}}, 1000000);
  const auto xy = dots(svg);
  const double columns = 500 - PlotCanvas::kLeft - PlotCanvas::kRight;
  EXPECT_GT(xy.size(), static_cast<std::size_t>(columns / 2));
  EXPECT_LT(xy.size(), static_cast<std::size_t>(4 * columns));
  const auto [lowest, highest] = std::minmax_element(
      xy.begin(), xy.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  const PlotCanvas canvas(options, 0.0, 1.0, -1.0, 1.0);
  EXPECT_NEAR(lowest->second, canvas.y()(1.0), 1.0);
  EXPECT_NEAR(highest->second, canvas.y()(-1.0), 1.0);
  EXPECT_LT(svg.size(), 20000u);
  // max_points still caps a series: every other cell is kept.
  EXPECT_LE(dots(scatter_plot(options, {{"sine", x, y, ""}}, 200)).size(), 200u);
}

TEST(AxisMap, IsAffine) {
  const AxisMap m{2.0, 4.0, 100.0, 300.0};
  EXPECT_DOUBLE_EQ(m(2.0), 100.0);
  EXPECT_DOUBLE_EQ(m(4.0), 300.0);
  EXPECT_DOUBLE_EQ(m(3.5), 250.0);
  const AxisMap flipped{0.0, 10.0, 250.0, 50.0};  // SVG y grows downward
  EXPECT_DOUBLE_EQ(flipped(10.0), 50.0);
}

TEST(LinePlot, NaNBreaksTheLineAndLongSeriesAreDecimated) {
  PlotOptions options;
  const Series s{"q1", vec({0, 1, 2, 3, 4}), vec({0, 1, kNaN, 3, 4}), ""};
  const std::string svg = line_plot(options, {s});
  const std::size_t d = svg.find(" d=\"M");
  ASSERT_NE(d, std::string::npos);
  const std::string path = svg.substr(d, svg.find('"', d + 4) - d);
  EXPECT_EQ(std::count(path.begin(), path.end(), 'M'), 2);
  EXPECT_EQ(std::count(path.begin(), path.end(), 'L'), 2);
  // 100 000 samples with one spike: at most 2 points per pixel column, spike kept.
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(100000, 0, 1);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(100000);
  y[61234] = 5.0;
  const std::string big = line_plot(options, {Series{"", x, y, ""}});
  EXPECT_LT(big.size(), 20000u);
  // The spike's top, at whole pixels: the second point of its column ("V44").
  EXPECT_NE(big.find("V" + std::to_string(std::lround(PlotCanvas::kTop))), std::string::npos);
  EXPECT_THROW(line_plot(options, {Series{"bad", vec({1, 2}), vec({1}), ""}}), Error);
}

TEST(LinePlot, EveryLegendEntryStaysInsideThePicture) {
  // The measured report's residual plots have five long series names: in one row above the plot
  // the first ones were drawn left of x = 0, so the traces "before" could not be told apart.
  PlotOptions options;
  options.title = "joint 1: residual";
  options.width = 900;
  options.height = 260;
  std::vector<Series> series;
  for (const char* name : {"Kt only", "after identification", "friction against the sensor",
                           "friction against the sensor + current low-pass",
                           "friction against the sensor + compensator trained against it"})
    series.push_back({name, vec({0, 1, 2}), vec({0, 1, 0}), ""});
  auto legend_rects = [](const std::string& svg) {
    const std::size_t g = svg.find("<g class=\"legend\">");
    EXPECT_NE(g, std::string::npos);
    std::vector<std::pair<double, double>> xy;
    const std::regex rect("<rect x=\"([-0-9.]+)\" y=\"([-0-9.]+)\"");
    const std::string legend = svg.substr(g);
    for (auto it = std::sregex_iterator(legend.begin(), legend.end(), rect);
         it != std::sregex_iterator(); ++it)
      xy.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
    return xy;
  };
  const std::string svg = line_plot(options, series);
  const auto rects = legend_rects(svg);
  ASSERT_EQ(rects.size(), series.size());
  std::smatch height;
  ASSERT_TRUE(std::regex_search(svg, height, std::regex("height=\"([0-9.]+)\" role")));
  const double svg_height = std::stod(height[1]);
  EXPECT_GT(svg_height, options.height);  // rows under the plot
  for (const auto& [x, y] : rects) {
    EXPECT_GE(x, 0.0);
    EXPECT_LE(x, options.width - 12.0);
    EXPECT_GT(y, options.height - 1.0);
    EXPECT_LE(y + 12.0, svg_height);
  }
  // Two short names keep their place: one row above the plot, right-aligned, same height.
  const std::string small = line_plot(options, {series[0], series[1]});
  const auto above = legend_rects(small);
  ASSERT_EQ(above.size(), 2u);
  for (const auto& [x, y] : above) {
    EXPECT_GE(x, PlotCanvas::kLeft);
    EXPECT_EQ(y, 26.0);
  }
  EXPECT_NE(small.find("height=\"260\" role"), std::string::npos);
}

TEST(BarChart, BarsStartAtZeroAndHaveOneValuePerGroup) {
  PlotOptions options;
  options.width = 400;
  options.height = 300;
  const std::string svg =
      bar_chart(options, {"static", "moving"},
                {{"nominal", {280.17, 100.0}, ""}, {"compensated", {31.96, 50.0}, ""}});
  // Every bar spans from its value down to y(0), the bottom of the plot area here.
  const std::regex bar(
      "<rect x=\"[-0-9.]+\" y=\"([-0-9.]+)\" width=\"[-0-9.]+\" height=\"([-0-9.]+)\"><title>");
  std::vector<double> tops;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), bar); it != std::sregex_iterator();
       ++it) {
    const double top = std::stod((*it)[1]), height = std::stod((*it)[2]);
    EXPECT_NEAR(top + height, 300 - PlotCanvas::kBottom, 0.11);
    tops.push_back(top);
  }
  ASSERT_EQ(tops.size(), 4u);  // series-major: nominal static, nominal moving, compensated ...
  const double bottom = 300 - PlotCanvas::kBottom;
  EXPECT_NEAR((bottom - tops[2]) / (bottom - tops[0]), 31.96 / 280.17, 2e-3);
  EXPECT_TRUE(test::check_tags(svg).empty()) << test::check_tags(svg);
  EXPECT_NE(svg.find(">static<"), std::string::npos);
  EXPECT_NE(svg.find(">280<"), std::string::npos);  // value label
  EXPECT_THROW(bar_chart(options, {"a"}, {{"x", {1.0, 2.0}, ""}}), Error);
  // A label wider than its bar (5 characters of ≈ 6 px in 24 px bars) keeps 2 digits, so that
  // neighbours' labels never run into each other; one that fits keeps 3.
  PlotOptions narrow;
  narrow.width = 400;
  const std::vector<std::string> joints{"1", "2", "3", "4"};
  const std::string crowded = bar_chart(
      narrow, joints,
      {{"a", {0.652, 1, 1, 1}, ""}, {"b", {0.595, 1, 1, 1}, ""}, {"c", {1, 1, 1, 1}, ""}});
  EXPECT_NE(crowded.find(">0.65<"), std::string::npos);
  EXPECT_EQ(crowded.find(">0.652<"), std::string::npos);
  const std::string roomy = bar_chart(options, {"one"}, {{"a", {0.652}, ""}});
  EXPECT_NE(roomy.find(">0.652<"), std::string::npos);
}

// Category names wider than their slot wrap after a space or a hyphen instead of running into
// their neighbours (diagnose's chart: 12 groups "j1 static-to-kinetic" … in 900 px).
TEST(BarChart, LongCategoryNamesWrapInsideTheirSlot) {
  PlotOptions options;
  options.width = 900;
  options.height = 320;
  std::vector<std::string> groups;
  for (int j = 1; j <= 4; ++j)
    for (const char* regime : {"static", "static-to-kinetic", "moving"})
      groups.push_back(std::string("j").append(std::to_string(j)).append(" ").append(regime));
  const std::string svg =
      bar_chart(options, groups, {{"before", std::vector<double>(12, 1.0), ""}});
  EXPECT_TRUE(test::check_tags(svg).empty()) << test::check_tags(svg);
  const double slot = (900 - PlotCanvas::kLeft - PlotCanvas::kRight) / 12.0;
  const std::regex line("<tspan x=\"[-0-9.]+\" dy=\"(0|13)\">([^<]*)</tspan>");
  int lines = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), line); it != std::sregex_iterator();
       ++it, ++lines) {
    const std::string text = (*it)[2];
    EXPECT_LE(7.0 * static_cast<double>(text.size()), slot + 7.0) << text;
  }
  EXPECT_GE(lines, 8);  // the four "static-to-kinetic" names on two or three lines each
  EXPECT_NE(svg.find(">j1 static-</tspan>"), std::string::npos);
  EXPECT_NE(svg.find(">to-kinetic</tspan>"), std::string::npos);
  EXPECT_NE(svg.find(">j1 static</text>"), std::string::npos);  // fits: one line, no tspan
}

TEST(Histogram, BinsAndShares) {
  EXPECT_EQ(bin_counts(vec({0, 0.1, 0.5, 0.99, 1.0, 2.0, kNaN}), 0.0, 1.0, 2),
            (std::vector<std::size_t>{2, 3}));
  const std::string svg =
      histogram({}, {{"before", vec({-1, 0, 0, 1}), ""}, {"after", vec({0, 0}), ""}}, 4);
  EXPECT_TRUE(test::check_tags(svg).empty()) << test::check_tags(svg);
  EXPECT_NE(svg.find("share of samples [%]"), std::string::npos);
}

TEST(TagChecker, CatchesUnbalancedMarkup) {
  EXPECT_TRUE(test::check_tags("<p>a<b>c</b></p><br>").empty());
  EXPECT_FALSE(test::check_tags("<p>a<b>c</p></b>").empty());
  EXPECT_FALSE(test::check_tags("<p>1 < 2</p>").empty());
  EXPECT_FALSE(test::check_tags("<p>a & b</p>").empty());
  EXPECT_FALSE(test::check_tags("<div>").empty());
}

/// A sample report with every element; written to $TPF_REPORT_SAMPLE when set (for viewing).
HtmlReport sample_report() {
  HtmlReport report("Friction diagnosis <arm4> & twin");
  report.mark_simulated();
  report.subtitle("log: excitation_twin.csv · 4 joints · 400 Hz · 600 s");
  report.heading("Residual per regime");
  report.paragraph(
      "RMSE of the current residual [mA] before and after adding the missing effect "
      "(held-out data). Values < 0 % mean the error got smaller.");
  Table table;
  table.caption = "Joint 2, current residual RMSE [mA]";
  table.header = {"regime", "samples", "nominal", "compensated", "change"};
  table.percent_column = 4;
  table.rows = {{"static", "52 311", format_number(280.17), format_number(31.96),
                 format_percent_change(280.17, 31.96)},
                {"static-to-kinetic", "1 204", format_number(270.95), format_number(124.81),
                 format_percent_change(270.95, 124.81)},
                {"moving", "184 020", format_number(88.4), format_number(91.2),
                 format_percent_change(88.4, 91.2)}};
  report.table(table);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  const Eigen::Index n = 4000;
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(n, 0.0, (n - 1) / 400.0);
  Eigen::VectorXd before(n), after(n), velocity(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    velocity[k] = 0.8 * std::sin(2 * std::numbers::pi * 0.2 * t[k]);
    before[k] = 120 * std::tanh(velocity[k] / 0.05) + 30 * velocity[k] + 15 * noise(rng);
    after[k] = 15 * noise(rng) + 5 * std::sin(t[k]);
  }
  before[1500] = kNaN;  // a dropped sample shows as a break
  PlotOptions line;
  line.title = "Current residual, joint 2";
  line.x_label = "time [s]";
  line.y_label = "residual [mA]";
  report.figure(
      line_plot(line, {{"nominal model", t, before, ""}, {"compensated", t, after, ""}}),
      "The nominal model leaves a velocity-sign-dependent offset (friction) in the residual.");
  PlotOptions scatter;
  scatter.title = "Residual vs joint velocity";
  scatter.x_label = "joint velocity dq2 [rad/s]";
  scatter.y_label = "residual [mA]";
  report.figure(
      scatter_plot(scatter, {{"before", velocity, before, ""}, {"after", velocity, after, ""}}));
  PlotOptions bars;
  bars.title = "RMSE per regime, joint 2";
  bars.y_label = "RMSE [mA]";
  report.figure(bar_chart(
      bars, {"static", "static-to-kinetic", "moving"},
      {{"nominal", {280.17, 270.95, 88.4}, ""}, {"compensated", {31.96, 124.81, 91.2}, ""}}));
  PlotOptions hist;
  hist.title = "Residual distribution";
  hist.x_label = "residual [mA]";
  report.figure(histogram(hist, {{"nominal", before, ""}, {"compensated", after, ""}}, 50));
  report.heading("Data quality");
  report.preformatted("240000 rows, 600.0 s at 400 Hz; 3 gaps; no missing values");
  report.list({"effort column: i (mA)", "acceleration: derived (filtfilt Butterworth, 20 Hz)"});
  return report;
}

TEST(HtmlReport, SampleReportIsWellFormedSelfContainedAndEscaped) {
  const std::string html = sample_report().html();
  EXPECT_EQ(test::check_tags(html), "");
  EXPECT_NE(html.find("<title>Friction diagnosis &lt;arm4&gt; &amp; twin</title>"),
            std::string::npos);
  EXPECT_NE(html.find("Values &lt; 0 % mean"), std::string::npos);
  EXPECT_NE(html.find("SIMULATED DATA"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("http://"),
            html.find("http://www.w3.org/2000/svg"));  // only the SVG namespace
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num better\">\u221288.6\u00a0%</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num worse\">+3.2\u00a0%</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>static-to-kinetic</td>"), std::string::npos);
  // A table wider than the page scrolls in its own box; numeric headers wrap.
  EXPECT_NE(html.find("<div class=\"table-scroll\"><table>"), std::string::npos);
  EXPECT_NE(html.find(".table-scroll { max-width: 100%; overflow-x: auto; }"), std::string::npos);
  EXPECT_EQ(html.find("th.num { text-align: right; font-variant-numeric: tabular-nums; "
                      "white-space: nowrap"),
            std::string::npos);
  // Plot ids are unique so clip paths do not collide.
  const std::regex ids("clipPath id=\"(plot[0-9]+)\"");
  std::set<std::string> seen;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), ids); it != std::sregex_iterator();
       ++it)
    EXPECT_TRUE(seen.insert((*it)[1]).second);
  EXPECT_EQ(seen.size(), 4u);
}

TEST(HtmlReport, WritesAtomically) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("tpf_report_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const HtmlReport report = sample_report();
  report.write(dir / "report.html");
  std::ostringstream text;
  text << std::ifstream(dir / "report.html").rdbuf();
  EXPECT_EQ(text.str(), report.html());
  EXPECT_GT(text.str().size(), 10000u);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            1);
  EXPECT_THROW(report.write(dir / "missing_dir" / "r.html"), Error);
  std::filesystem::remove_all(dir);
  if (const char* out = std::getenv("TPF_REPORT_SAMPLE")) report.write(out);
}

}  // namespace
}  // namespace tpf::offline
