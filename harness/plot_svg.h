// Hand-written SVG time-series plots (no dependencies) for `efc play` logs.
//
// One stacked panel per PlotPanel, all sharing the time axis t. Each panel has a
// title, axes with round-number ticks, gridlines, a legend and one colour per
// series. Non-finite values (NaN, inf) leave gaps: each contiguous finite run of a
// series is one <polyline> (a series without gaps is exactly one polyline; an empty
// or all-NaN series has a legend entry but no polyline). Series longer than
// kPlotMaxPointsPerSeries are decimated by min/max per pixel-column bucket, so
// steps and spikes stay visible and a series never exceeds that many points.
// A constant series gets a small range around its value. All text is XML-escaped.
#ifndef EFC_HARNESS_PLOT_SVG_H_
#define EFC_HARNESS_PLOT_SVG_H_

#include <string>
#include <vector>

namespace efc {

struct PlotSeries {
  std::string label;
  std::vector<double> values;  // same length as t (extra values are ignored)
};

struct PlotPanel {
  std::string title;
  std::string y_label;
  std::vector<PlotSeries> series;
};

constexpr int kPlotMaxPointsPerSeries = 2000;

// One stacked panel per entry; shared time axis. False with *error on I/O failure.
bool write_plot_svg(const std::string& path, const std::vector<double>& t,
                    const std::vector<PlotPanel>& panels, std::string* error);
std::string plot_svg(const std::vector<double>& t, const std::vector<PlotPanel>& panels);

// Helpers, exposed for tests.
std::string xml_escape(const std::string& s);
// Round-number ticks (1, 2, 5 x 10^k) covering [lo, hi]; about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target);

}  // namespace efc

#endif  // EFC_HARNESS_PLOT_SVG_H_
