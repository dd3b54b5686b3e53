// The SVG plot: well-formed, one polyline per series, escaped labels, bounded size.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>

#include "harness/plot_svg.h"

using namespace efc;

namespace {
size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}
}  // namespace

TEST(PlotSvg, OnePolylinePerSeriesWithEscapedLabels) {
  std::vector<double> t, a, b;
  for (int i = 0; i <= 100; ++i) {
    t.push_back(i * 0.01);
    a.push_back(std::sin(i * 0.1));
    b.push_back(i < 50 ? 0 : 1);
  }
  const std::string svg = plot_svg(t, {{"f: <lamp> & \"x\"", "rad", {{"s_R", a}}},
                                       {"f: light", "lm", {{"s_E", b}, {"measured", b}}}});
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_EQ(count(svg, "<polyline"), 3u);
  EXPECT_NE(svg.find("f: &lt;lamp&gt; &amp; &quot;x&quot;"), std::string::npos);
  EXPECT_EQ(svg.find("<lamp>"), std::string::npos);
  EXPECT_EQ(count(svg, "<g>"), count(svg, "</g>"));
}

TEST(PlotSvg, FlatEmptyAndGappySeriesDoNotBreak) {
  std::vector<double> t{0, 1, 2, 3}, flat{5, 5, 5, 5}, gap{1, NAN, 2, 3};
  const std::string svg = plot_svg(t, {{"flat", "C", {{"T", flat}}}, {"gap", "m", {{"q", gap}}}});
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
  EXPECT_EQ(count(svg, "<polyline"), 3u);  // the gap splits one series in two
  EXPECT_NO_THROW(plot_svg({}, {{"empty", "", {{"none", {}}}}}));
}

TEST(PlotSvg, LongLogsAreDecimatedButKeepSteps) {
  std::vector<double> t, v;
  for (int i = 0; i < 200000; ++i) {
    t.push_back(i * 1e-4);
    v.push_back(i % 20000 < 10000 ? 0 : 1);  // a square wave
  }
  const std::string svg = plot_svg(t, {{"square", "", {{"v", v}}}});
  const std::string points = svg.substr(svg.find("points=\""));
  const size_t n = count(points.substr(0, points.find("\"/>")), ",");
  EXPECT_LT(n, 2000u);
  EXPECT_GT(n, 20u);
  EXPECT_LT(svg.size(), 200000u);
}

TEST(PlotSvg, UnwritablePathIsAnError) {
  std::string error;
  EXPECT_FALSE(write_plot_svg("/nonexistent/dir/plot.svg", {0, 1}, {{"p", "", {{"s", {0, 1}}}}}, &error));
  EXPECT_NE(error.find("cannot write"), std::string::npos);
}
