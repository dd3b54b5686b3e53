// SVG plots of a playback log: one stacked panel per entry on a shared time
// axis (the harness gives each function a panel for s_R and one for s_E and
// measured). Hand-written SVG, no dependencies.
#pragma once

#include <string>
#include <vector>

namespace efc {

struct PlotSeries {
  std::string label;
  std::vector<double> values;  // same length as t; NaN leaves a gap
};

struct PlotPanel {
  std::string title;
  std::string y_label;  // the unit
  std::vector<PlotSeries> series;
};

std::string plot_svg(const std::vector<double>& t, const std::vector<PlotPanel>& panels);
// False with *error when the file cannot be written.
bool write_plot_svg(const std::string& path, const std::vector<double>& t,
                    const std::vector<PlotPanel>& panels, std::string* error);

}  // namespace efc
