#include "harness/plot_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace efc {
namespace {

// Layout, in SVG user units (pixels).
constexpr double kLeft = 78;          // room for y tick labels and the y label
constexpr double kPlotW = 700;        // plot area width
constexpr double kPanelH = 200;       // plot area height per panel
constexpr double kPanelTitleH = 28;   // above each plot area
constexpr double kPanelGap = 34;      // below each plot area (x tick labels)
constexpr double kTop = 8;
constexpr double kBottom = 30;        // below the last panel: x axis label
constexpr double kCharW = 7.0;        // rough width of a 12px sans-serif glyph

const char* const kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                                "#8c564b", "#e377c2", "#17becf", "#7f7f7f", "#bcbd22"};
constexpr int kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);

std::string num(double v) {  // coordinates
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  std::string s = buf;
  // Trim trailing zeros for compactness: "12.50" -> "12.5", "3.00" -> "3".
  size_t dot = s.find('.');
  if (dot != std::string::npos) {
    size_t end = s.find_last_not_of('0');
    if (end == dot) end--;
    s.erase(end + 1);
  }
  if (s == "-0") s = "0";
  return s;
}

double nice_step(double range, int target) {
  if (!(range > 0) || !std::isfinite(range)) return 1.0;
  if (target < 1) target = 1;
  double raw = range / target;
  double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double f = raw / mag;
  double nf = f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10;
  return nf * mag;
}

std::string tick_label(double v, double step) {
  char buf[48];
  if (std::fabs(v) < step * 1e-9) v = 0;
  double av = std::fabs(v);
  if ((av != 0 && (av >= 1e7 || av < 1e-4)) || step < 1e-4) {
    std::snprintf(buf, sizeof buf, "%.4g", v);
  } else {
    int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  }
  std::string s = buf;
  if (s == "-0") s = "0";
  return s;
}

struct Range {
  double lo = 0, hi = 1;
};

// Finite [min, max] of values[0, n); false if none.
bool finite_range(const std::vector<double>& v, size_t n, double* lo, double* hi) {
  bool any = false;
  for (size_t i = 0; i < n && i < v.size(); ++i) {
    double x = v[i];
    if (!std::isfinite(x)) continue;
    if (!any) {
      *lo = *hi = x;
      any = true;
    } else {
      *lo = std::min(*lo, x);
      *hi = std::max(*hi, x);
    }
  }
  return any;
}

Range pad_flat(double lo, double hi) {
  if (hi > lo) return {lo, hi};
  double pad = lo != 0 ? std::fabs(lo) * 0.1 : 1.0;
  return {lo - pad, hi + pad};
}

struct Pt {
  double x, y;
};

// Screen-space points of one series, split into contiguous finite runs, decimated
// to at most kPlotMaxPointsPerSeries points by min/max per x-pixel bucket.
std::vector<std::vector<Pt>> series_segments(const std::vector<double>& t,
                                              const std::vector<double>& v, Range xr,
                                              Range yr, double x0, double y0) {
  const size_t n = std::min(t.size(), v.size());
  auto sx = [&](double tt) { return x0 + (tt - xr.lo) / (xr.hi - xr.lo) * kPlotW; };
  auto sy = [&](double vv) { return y0 + kPanelH - (vv - yr.lo) / (yr.hi - yr.lo) * kPanelH; };
  std::vector<std::vector<Pt>> segs;
  bool gap = true;  // next finite point starts a new segment
  auto push = [&](double tt, double vv) {
    if (gap || segs.empty()) segs.emplace_back();
    gap = false;
    segs.back().push_back({sx(tt), sy(vv)});
  };

  size_t finite = 0;
  for (size_t i = 0; i < n; ++i)
    if (std::isfinite(t[i]) && std::isfinite(v[i])) ++finite;

  if (finite <= static_cast<size_t>(kPlotMaxPointsPerSeries)) {
    for (size_t i = 0; i < n; ++i) {
      if (std::isfinite(t[i]) && std::isfinite(v[i]))
        push(t[i], v[i]);
      else
        gap = true;
    }
    return segs;
  }

  // Min/max per bucket; a bucket emits its extremes in time order, so a step inside
  // one pixel column is a vertical stroke. A non-finite value between two buckets
  // breaks the line; one inside a bucket is below a pixel and is not drawn.
  const int buckets = std::min(kPlotMaxPointsPerSeries / 2, static_cast<int>(kPlotW));
  long cur = -1;
  size_t imin = 0, imax = 0;
  bool gap_pending = false;  // non-finite seen since the last flushed bucket
  auto flush = [&]() {
    if (cur < 0) return;
    size_t a = std::min(imin, imax), b = std::max(imin, imax);
    push(t[a], v[a]);
    if (b != a) push(t[b], v[b]);
    cur = -1;
  };
  for (size_t i = 0; i < n; ++i) {
    if (!(std::isfinite(t[i]) && std::isfinite(v[i]))) {
      gap_pending = true;
      continue;
    }
    double f = (t[i] - xr.lo) / (xr.hi - xr.lo);
    long b = static_cast<long>(std::floor(f * buckets));
    b = std::max(0L, std::min(static_cast<long>(buckets - 1), b));
    if (b != cur) {
      flush();
      if (gap_pending) gap = true;
      gap_pending = false;
      cur = b;
      imin = imax = i;
    } else {
      if (v[i] < v[imin]) imin = i;
      if (v[i] > v[imax]) imax = i;
    }
  }
  flush();
  return segs;
}

}  // namespace

std::string xml_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (unsigned char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // Control characters other than tab/newline are not allowed in XML 1.0.
        if (c < 0x20 && c != '\t' && c != '\n' && c != '\r')
          out += '?';
        else
          out += static_cast<char>(c);
    }
  }
  return out;
}

namespace {

std::vector<double> ticks_with_step(double lo, double hi, double step) {
  std::vector<double> ticks;
  double eps = step * 1e-9;
  double first = std::ceil((lo - eps) / step);
  for (int k = 0; k < 1000; ++k) {
    double v = (first + k) * step;
    if (v > hi + eps) break;
    if (std::fabs(v) < eps) v = 0;
    ticks.push_back(v);
  }
  return ticks;
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) return {};
  if (hi < lo) std::swap(lo, hi);
  if (hi == lo) return {lo};
  return ticks_with_step(lo, hi, nice_step(hi - lo, target));
}

std::string plot_svg(const std::vector<double>& t, const std::vector<PlotPanel>& panels) {
  // Shared time range.
  Range xr;
  {
    double lo = 0, hi = 1;
    if (finite_range(t, t.size(), &lo, &hi)) {
      if (hi > lo)
        xr = {lo, hi};
      else
        xr = {lo - 0.5, hi + 0.5};
    }
  }
  const double xstep = nice_step(xr.hi - xr.lo, 8);
  const std::vector<double> xticks = ticks_with_step(xr.lo, xr.hi, xstep);

  size_t longest = 0;
  for (const PlotPanel& p : panels)
    for (const PlotSeries& s : p.series) longest = std::max(longest, s.label.size());
  const double legend_w = std::min(420.0, 40 + kCharW * static_cast<double>(longest));
  const double width = kLeft + kPlotW + 16 + legend_w + 10;
  const size_t np = std::max<size_t>(panels.size(), 1);
  const double height =
      kTop + static_cast<double>(np) * (kPanelTitleH + kPanelH + kPanelGap) + kBottom;

  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width) << "\" height=\""
    << num(height) << "\" viewBox=\"0 0 " << num(width) << " " << num(height)
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  o << "<rect x=\"0\" y=\"0\" width=\"" << num(width) << "\" height=\"" << num(height)
    << "\" fill=\"white\"/>\n";

  const size_t n = t.size();
  for (size_t pi = 0; pi < panels.size(); ++pi) {
    const PlotPanel& panel = panels[pi];
    const double top = kTop + static_cast<double>(pi) * (kPanelTitleH + kPanelH + kPanelGap);
    const double x0 = kLeft, y0 = top + kPanelTitleH;

    // Y range over all series, expanded to round tick bounds.
    bool any = false;
    double lo = 0, hi = 1;
    for (const PlotSeries& s : panel.series) {
      double a, b;
      if (!finite_range(s.values, n, &a, &b)) continue;
      if (!any) {
        lo = a;
        hi = b;
        any = true;
      } else {
        lo = std::min(lo, a);
        hi = std::max(hi, b);
      }
    }
    Range yr = any ? pad_flat(lo, hi) : Range{0, 1};
    double ystep = nice_step(yr.hi - yr.lo, 5);
    yr.lo = std::floor(yr.lo / ystep + 1e-9) * ystep;
    yr.hi = std::ceil(yr.hi / ystep - 1e-9) * ystep;
    if (!(yr.hi > yr.lo)) yr.hi = yr.lo + ystep;
    const std::vector<double> yticks = ticks_with_step(yr.lo, yr.hi, ystep);
    {  // A little room beyond the outer ticks, so lines at the limits stay off the frame.
      const double pad = 0.04 * (yr.hi - yr.lo);
      yr.lo -= pad;
      yr.hi += pad;
    }
    auto sx = [&](double tt) { return x0 + (tt - xr.lo) / (xr.hi - xr.lo) * kPlotW; };
    auto sy = [&](double vv) { return y0 + kPanelH - (vv - yr.lo) / (yr.hi - yr.lo) * kPanelH; };

    o << "<g class=\"panel\">\n";
    o << "<text class=\"title\" x=\"" << num(x0) << "\" y=\"" << num(top + 18)
      << "\" font-size=\"14\" font-weight=\"bold\">" << xml_escape(panel.title) << "</text>\n";
    o << "<clipPath id=\"clip" << pi << "\"><rect x=\"" << num(x0) << "\" y=\"" << num(y0)
      << "\" width=\"" << num(kPlotW) << "\" height=\"" << num(kPanelH)
      << "\"/></clipPath>\n";

    // Gridlines.
    o << "<g class=\"grid\" stroke=\"#dddddd\" stroke-width=\"1\">\n";
    for (double xt : xticks)
      o << "<line x1=\"" << num(sx(xt)) << "\" y1=\"" << num(y0) << "\" x2=\"" << num(sx(xt))
        << "\" y2=\"" << num(y0 + kPanelH) << "\"/>\n";
    for (double yt : yticks)
      o << "<line x1=\"" << num(x0) << "\" y1=\"" << num(sy(yt)) << "\" x2=\""
        << num(x0 + kPlotW) << "\" y2=\"" << num(sy(yt)) << "\"/>\n";
    o << "</g>\n";

    // Axes frame, ticks and tick labels.
    o << "<rect class=\"axes\" x=\"" << num(x0) << "\" y=\"" << num(y0) << "\" width=\""
      << num(kPlotW) << "\" height=\"" << num(kPanelH)
      << "\" fill=\"none\" stroke=\"black\" stroke-width=\"1\"/>\n";
    o << "<g class=\"xticks\" stroke=\"black\">\n";
    for (double xt : xticks)
      o << "<line x1=\"" << num(sx(xt)) << "\" y1=\"" << num(y0 + kPanelH) << "\" x2=\""
        << num(sx(xt)) << "\" y2=\"" << num(y0 + kPanelH + 5) << "\"/>\n";
    o << "</g>\n<g class=\"xlabels\" text-anchor=\"middle\">\n";
    for (double xt : xticks)
      o << "<text x=\"" << num(sx(xt)) << "\" y=\"" << num(y0 + kPanelH + 18) << "\">"
        << xml_escape(tick_label(xt, xstep)) << "</text>\n";
    o << "</g>\n<g class=\"yticks\" stroke=\"black\">\n";
    for (double yt : yticks)
      o << "<line x1=\"" << num(x0 - 5) << "\" y1=\"" << num(sy(yt)) << "\" x2=\"" << num(x0)
        << "\" y2=\"" << num(sy(yt)) << "\"/>\n";
    o << "</g>\n<g class=\"ylabels\" text-anchor=\"end\">\n";
    for (double yt : yticks)
      o << "<text x=\"" << num(x0 - 8) << "\" y=\"" << num(sy(yt) + 4) << "\">"
        << xml_escape(tick_label(yt, ystep)) << "</text>\n";
    o << "</g>\n";
    const double ylx = 16, yly = y0 + kPanelH / 2;
    o << "<text class=\"ylabel\" x=\"" << num(ylx) << "\" y=\"" << num(yly)
      << "\" text-anchor=\"middle\" transform=\"rotate(-90 " << num(ylx) << " " << num(yly)
      << ")\">" << xml_escape(panel.y_label) << "</text>\n";

    // Series.
    for (size_t si = 0; si < panel.series.size(); ++si) {
      const PlotSeries& s = panel.series[si];
      const char* colour = kPalette[si % kPaletteSize];
      // Past the palette, vary the dash pattern so series stay distinguishable.
      std::string dash;
      if (si >= static_cast<size_t>(kPaletteSize))
        dash = " stroke-dasharray=\"" + std::to_string(2 + 2 * (si / kPaletteSize)) + " 3\"";
      o << "<g class=\"series\" stroke=\"" << colour << "\"" << dash
        << " fill=\"none\" stroke-width=\"1.5\" stroke-linejoin=\"round\""
        << " stroke-linecap=\"round\" clip-path=\"url(#clip" << pi << ")\">\n";
      for (const std::vector<Pt>& seg : series_segments(t, s.values, xr, yr, x0, y0)) {
        o << "<polyline points=\"";
        for (size_t k = 0; k < seg.size(); ++k) {
          if (k) o << ' ';
          o << num(seg[k].x) << ',' << num(seg[k].y);
        }
        if (seg.size() == 1) o << ' ' << num(seg[0].x) << ',' << num(seg[0].y);  // a dot
        o << "\"/>\n";
      }
      o << "</g>\n";
    }

    // Legend.
    const double lx = x0 + kPlotW + 16;
    o << "<g class=\"legend\">\n";
    for (size_t si = 0; si < panel.series.size(); ++si) {
      const double ly = y0 + 10 + 18 * static_cast<double>(si);
      std::string dash;
      if (si >= static_cast<size_t>(kPaletteSize))
        dash = " stroke-dasharray=\"" + std::to_string(2 + 2 * (si / kPaletteSize)) + " 3\"";
      o << "<line x1=\"" << num(lx) << "\" y1=\"" << num(ly) << "\" x2=\"" << num(lx + 24)
        << "\" y2=\"" << num(ly) << "\" stroke=\"" << kPalette[si % kPaletteSize] << "\""
        << dash << " stroke-width=\"2\"/>\n";
      o << "<text x=\"" << num(lx + 30) << "\" y=\"" << num(ly + 4) << "\">"
        << xml_escape(panel.series[si].label) << "</text>\n";
    }
    o << "</g>\n</g>\n";
  }

  const double last_axis = kTop + static_cast<double>(np) * (kPanelTitleH + kPanelH + kPanelGap);
  o << "<text class=\"xlabel\" x=\"" << num(kLeft + kPlotW / 2) << "\" y=\""
    << num(last_axis + 12) << "\" text-anchor=\"middle\">t (s)</text>\n";
  o << "</svg>\n";
  return o.str();
}

bool write_plot_svg(const std::string& path, const std::vector<double>& t,
                    const std::vector<PlotPanel>& panels, std::string* error) {
  const std::string svg = plot_svg(t, panels);
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) {
    if (error) *error = "cannot open " + path + " for writing";
    return false;
  }
  f.write(svg.data(), static_cast<std::streamsize>(svg.size()));
  f.close();
  if (!f) {
    if (error) *error = "failed to write " + path;
    return false;
  }
  return true;
}

}  // namespace efc
