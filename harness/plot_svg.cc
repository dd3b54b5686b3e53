#include "harness/plot_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace efc {
namespace {

constexpr double kWidth = 900, kPanelHeight = 180, kLeft = 70, kRight = 150, kTop = 30,
                 kGap = 40;
const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"};

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// Round tick spacing: 1, 2 or 5 times a power of ten, about `count` ticks.
double tick_step(double span, int count) {
  if (!(span > 0)) return 1;
  const double raw = span / count;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

// Reduces a series to at most two points (min and max) per pixel column, so a
// step stays a step however long the log is.
std::vector<std::pair<double, double>> decimate(const std::vector<double>& t,
                                                const std::vector<double>& v, double t0,
                                                double t1, int columns) {
  std::vector<std::pair<double, double>> out;
  const size_t n = std::min(t.size(), v.size());
  if (n <= static_cast<size_t>(2 * columns)) {
    for (size_t i = 0; i < n; ++i) out.push_back({t[i], v[i]});
    return out;
  }
  int bucket = -1;
  size_t lo = 0, hi = 0;
  auto flush = [&](int b) {
    if (b < 0) return;
    if (lo <= hi) {
      out.push_back({t[lo], v[lo]});
      if (hi != lo) out.push_back({t[hi], v[hi]});
    } else {
      out.push_back({t[hi], v[hi]});
      out.push_back({t[lo], v[lo]});
    }
  };
  for (size_t i = 0; i < n; ++i) {
    const int b = t1 > t0 ? static_cast<int>((t[i] - t0) / (t1 - t0) * columns) : 0;
    if (b != bucket || std::isnan(v[i])) {
      flush(bucket);
      bucket = b;
      lo = hi = i;
      if (std::isnan(v[i])) out.push_back({t[i], v[i]});
      continue;
    }
    if (v[i] < v[lo]) lo = i;
    if (v[i] > v[hi]) hi = i;
  }
  flush(bucket);
  return out;
}

}  // namespace

std::string plot_svg(const std::vector<double>& t, const std::vector<PlotPanel>& panels) {
  const double plot_w = kWidth - kLeft - kRight;
  const double height = kTop + panels.size() * (kPanelHeight + kGap) + 20;
  double t0 = t.empty() ? 0 : t.front(), t1 = t.empty() ? 1 : t.back();
  if (!(t1 > t0)) t1 = t0 + 1;
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << height
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  o << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  for (size_t p = 0; p < panels.size(); ++p) {
    const PlotPanel& panel = panels[p];
    const double top = kTop + p * (kPanelHeight + kGap);
    double lo = INFINITY, hi = -INFINITY;
    for (const PlotSeries& s : panel.series)
      for (double v : s.values)
        if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!std::isfinite(lo)) lo = 0, hi = 1;
    if (hi - lo < 1e-12 * (1 + std::fabs(hi))) lo -= 0.5, hi += 0.5;  // a flat series
    const double pad = 0.05 * (hi - lo);
    lo -= pad;
    hi += pad;
    auto X = [&](double tt) { return kLeft + (tt - t0) / (t1 - t0) * plot_w; };
    auto Y = [&](double v) { return top + kPanelHeight - (v - lo) / (hi - lo) * kPanelHeight; };
    o << "<g>\n<text x=\"" << kLeft << "\" y=\"" << top - 8 << "\" font-weight=\"bold\">"
      << escape(panel.title) << "</text>\n";
    o << "<text x=\"12\" y=\"" << top + kPanelHeight / 2 << "\" transform=\"rotate(-90 12 "
      << top + kPanelHeight / 2 << ")\" text-anchor=\"middle\">" << escape(panel.y_label)
      << "</text>\n";
    const double ys = tick_step(hi - lo, 5);
    for (double v = std::ceil(lo / ys) * ys; v <= hi; v += ys) {
      o << "<line x1=\"" << kLeft << "\" x2=\"" << kLeft + plot_w << "\" y1=\"" << Y(v) << "\" y2=\""
        << Y(v) << "\" stroke=\"#e0e0e0\"/>\n";
      o << "<text x=\"" << kLeft - 4 << "\" y=\"" << Y(v) + 4 << "\" text-anchor=\"end\">"
        << num(std::fabs(v) < ys * 1e-9 ? 0 : v) << "</text>\n";
    }
    const double xs = tick_step(t1 - t0, 8);
    for (double tt = std::ceil(t0 / xs) * xs; tt <= t1 + 1e-12; tt += xs) {
      o << "<line x1=\"" << X(tt) << "\" x2=\"" << X(tt) << "\" y1=\"" << top << "\" y2=\""
        << top + kPanelHeight << "\" stroke=\"#e0e0e0\"/>\n";
      o << "<text x=\"" << X(tt) << "\" y=\"" << top + kPanelHeight + 14
        << "\" text-anchor=\"middle\">" << num(tt) << "</text>\n";
    }
    o << "<rect x=\"" << kLeft << "\" y=\"" << top << "\" width=\"" << plot_w << "\" height=\""
      << kPanelHeight << "\" fill=\"none\" stroke=\"black\"/>\n";
    for (size_t s = 0; s < panel.series.size(); ++s) {
      const PlotSeries& series = panel.series[s];
      const char* colour = kColours[s % (sizeof kColours / sizeof *kColours)];
      std::ostringstream pts;
      size_t count = 0;
      auto emit = [&]() {
        if (count > 0)
          o << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\" points=\""
            << pts.str() << "\"/>\n";
        pts.str("");
        count = 0;
      };
      for (const auto& [tt, v] : decimate(t, series.values, t0, t1, static_cast<int>(plot_w))) {
        if (!std::isfinite(v)) {  // a gap
          emit();
          continue;
        }
        pts << (count ? " " : "") << num(X(tt)) << "," << num(Y(v));
        ++count;
      }
      emit();
      const double ly = top + 14 + 16 * s;
      o << "<line x1=\"" << kLeft + plot_w + 10 << "\" x2=\"" << kLeft + plot_w + 30 << "\" y1=\""
        << ly - 4 << "\" y2=\"" << ly - 4 << "\" stroke=\"" << colour << "\" stroke-width=\"2\"/>\n";
      o << "<text x=\"" << kLeft + plot_w + 34 << "\" y=\"" << ly << "\">" << escape(series.label)
        << "</text>\n";
    }
    o << "</g>\n";
  }
  o << "<text x=\"" << kLeft + plot_w / 2 << "\" y=\"" << height - 4
    << "\" text-anchor=\"middle\">time (s)</text>\n</svg>\n";
  return o.str();
}

bool write_plot_svg(const std::string& path, const std::vector<double>& t,
                    const std::vector<PlotPanel>& panels, std::string* error) {
  std::ofstream out(path);
  if (out) out << plot_svg(t, panels);
  if (!out) {
    *error = "cannot write '" + path + "'";
    return false;
  }
  return true;
}

}  // namespace efc
