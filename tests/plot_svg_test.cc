// SVG plots of playback logs: well-formed XML, one polyline per series (per finite
// run), escaped labels, robust to constant/empty/NaN series, bounded point counts.
//
// libtinyxml2-dev is not installed, so the test carries a small strict XML checker
// (tags balanced, attributes quoted, only the predefined/numeric entities, no raw
// '<' or '&' in text) that also builds a tiny DOM for the structural checks.
#include "harness/plot_svg.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Node {
  std::string name;
  std::map<std::string, std::string> attrs;
  std::vector<std::unique_ptr<Node>> children;
  std::string text;  // concatenated character data directly inside
  std::string attr(const std::string& k) const {
    auto it = attrs.find(k);
    return it == attrs.end() ? "" : it->second;
  }
};

class XmlChecker {
 public:
  explicit XmlChecker(const std::string& s) : s_(s) {}

  // Parses the whole document; returns the root or null with error().
  std::unique_ptr<Node> parse() {
    skip_ws();
    if (s_.compare(i_, 5, "<?xml") == 0) {
      size_t e = s_.find("?>", i_);
      if (e == std::string::npos) return fail("unterminated XML declaration");
      i_ = e + 2;
    }
    skip_misc();
    if (i_ >= s_.size() || s_[i_] != '<') return fail("no root element");
    auto root = element();
    if (!root) return nullptr;
    skip_misc();
    if (i_ != s_.size()) return fail("content after the root element");
    return root;
  }
  const std::string& error() const { return err_; }

 private:
  std::unique_ptr<Node> fail(const std::string& m) {
    if (err_.empty()) err_ = m + " at offset " + std::to_string(i_);
    return nullptr;
  }
  void skip_ws() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  void skip_misc() {
    for (;;) {
      skip_ws();
      if (s_.compare(i_, 4, "<!--") == 0) {
        size_t e = s_.find("-->", i_);
        if (e == std::string::npos) return;
        i_ = e + 3;
      } else {
        return;
      }
    }
  }
  static bool name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == ':'; }
  static bool name_char(char c) {
    return name_start(c) || std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '.';
  }
  bool name(std::string* out) {
    if (i_ >= s_.size() || !name_start(s_[i_])) return false;
    size_t b = i_;
    while (i_ < s_.size() && name_char(s_[i_])) ++i_;
    *out = s_.substr(b, i_ - b);
    return true;
  }
  // Decodes character data up to `stop`, validating entities.
  bool chars(char stop, std::string* out) {
    while (i_ < s_.size() && s_[i_] != stop) {
      char c = s_[i_];
      if (c == '<') return false;
      if (c == '&') {
        size_t e = s_.find(';', i_);
        if (e == std::string::npos || e - i_ > 10) return false;
        std::string ent = s_.substr(i_ + 1, e - i_ - 1);
        if (ent == "amp") {
          *out += '&';
        } else if (ent == "lt") {
          *out += '<';
        } else if (ent == "gt") {
          *out += '>';
        } else if (ent == "quot") {
          *out += '"';
        } else if (ent == "apos") {
          *out += '\'';
        } else if (ent.size() > 1 && ent[0] == '#') {
          *out += '?';
        } else {
          return false;
        }
        i_ = e + 1;
        continue;
      }
      if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r')
        return false;
      *out += c;
      ++i_;
    }
    return true;
  }
  std::unique_ptr<Node> element() {
    ++i_;  // '<'
    auto node = std::make_unique<Node>();
    if (!name(&node->name)) return fail("bad element name");
    for (;;) {
      size_t before = i_;
      skip_ws();
      if (i_ >= s_.size()) return fail("unterminated start tag");
      if (s_.compare(i_, 2, "/>") == 0) {
        i_ += 2;
        return node;
      }
      if (s_[i_] == '>') {
        ++i_;
        break;
      }
      if (i_ == before) return fail("attributes need whitespace between them");
      std::string an;
      if (!name(&an)) return fail("bad attribute name");
      if (node->attrs.count(an)) return fail("duplicate attribute " + an);
      if (i_ >= s_.size() || s_[i_] != '=') return fail("attribute without '='");
      ++i_;
      if (i_ >= s_.size() || (s_[i_] != '"' && s_[i_] != '\'')) return fail("unquoted attribute");
      char q = s_[i_++];
      std::string val;
      if (!chars(q, &val) || i_ >= s_.size()) return fail("bad attribute value");
      ++i_;
      node->attrs[an] = val;
    }
    for (;;) {
      if (!chars('<', &node->text)) return fail("bad character data");
      if (i_ >= s_.size()) return fail("unclosed element " + node->name);
      if (s_.compare(i_, 4, "<!--") == 0) {
        size_t e = s_.find("-->", i_);
        if (e == std::string::npos) return fail("unterminated comment");
        i_ = e + 3;
      } else if (s_.compare(i_, 2, "</") == 0) {
        i_ += 2;
        std::string end;
        if (!name(&end) || end != node->name) return fail("mismatched end tag for " + node->name);
        skip_ws();
        if (i_ >= s_.size() || s_[i_] != '>') return fail("bad end tag");
        ++i_;
        return node;
      } else {
        auto child = element();
        if (!child) return nullptr;
        node->children.push_back(std::move(child));
      }
    }
  }

  const std::string& s_;
  size_t i_ = 0;
  std::string err_;
};

void collect(const Node& n, const std::string& name, std::vector<const Node*>* out) {
  if (n.name == name) out->push_back(&n);
  for (const auto& c : n.children) collect(*c, name, out);
}
std::vector<const Node*> find_all(const Node& n, const std::string& name) {
  std::vector<const Node*> out;
  collect(n, name, &out);
  return out;
}
std::vector<const Node*> children_with_class(const Node& n, const std::string& cls) {
  std::vector<const Node*> out;
  for (const auto& c : n.children)
    if (c->attr("class") == cls) out.push_back(c.get());
  return out;
}

struct P {
  double x, y;
};
std::vector<P> points_of(const Node& polyline) {
  std::vector<P> pts;
  std::istringstream in(polyline.attr("points"));
  std::string tok;
  while (in >> tok) {
    size_t c = tok.find(',');
    EXPECT_NE(c, std::string::npos) << tok;
    if (c == std::string::npos) continue;
    pts.push_back({std::stod(tok.substr(0, c)), std::stod(tok.substr(c + 1))});
  }
  return pts;
}

void check_no_nonfinite(const Node& n) {
  for (const auto& kv : n.attrs) {
    std::string v = kv.second;
    for (char& c : v) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    EXPECT_EQ(v.find("nan"), std::string::npos) << n.name << " " << kv.first << "=" << v;
    EXPECT_EQ(v.find("inf"), std::string::npos) << n.name << " " << kv.first << "=" << v;
  }
  for (const auto& c : n.children) check_no_nonfinite(*c);
}

std::unique_ptr<Node> parse_ok(const std::string& svg) {
  XmlChecker x(svg);
  auto root = x.parse();
  EXPECT_NE(root, nullptr) << x.error() << "\n" << svg.substr(0, 2000);
  if (root) {
    EXPECT_EQ(root->name, "svg");
    // Never let a NaN or infinity leak into coordinates (any attribute value).
    check_no_nonfinite(*root);
  }
  return root;
}

std::vector<double> time_axis(size_t n, double dt) {
  std::vector<double> t(n);
  for (size_t i = 0; i < n; ++i) t[i] = i * dt;
  return t;
}

const double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(PlotSvg, WellFormedWithOnePolylinePerSeries) {
  std::vector<double> t = time_axis(1001, 0.01);
  std::vector<double> sr(t.size()), se(t.size()), meas(t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    sr[i] = 0.5 * t[i] / 10.0;
    se[i] = 100 * sr[i];
    meas[i] = se[i] * (1 - std::exp(-t[i]));
  }
  std::vector<efc::PlotPanel> panels = {
      {"dimmer: receptor knob", "rad", {{"dimmer.s_R", sr}}},
      {"dimmer: effect", "lm", {{"dimmer.s_E", se}, {"dimmer.measured", meas}}}};
  std::string svg = efc::plot_svg(t, panels);
  auto root = parse_ok(svg);
  ASSERT_NE(root, nullptr);
  auto panel_nodes = children_with_class(*root, "panel");
  ASSERT_EQ(panel_nodes.size(), 2u);
  const double W = std::stod(root->attr("width")), H = std::stod(root->attr("height"));
  for (size_t p = 0; p < 2; ++p) {
    auto series = children_with_class(*panel_nodes[p], "series");
    ASSERT_EQ(series.size(), panels[p].series.size());
    std::set<std::string> colours;
    for (const Node* s : series) {
      colours.insert(s->attr("stroke"));
      auto polys = find_all(*s, "polyline");
      ASSERT_EQ(polys.size(), 1u);
      auto pts = points_of(*polys[0]);
      EXPECT_EQ(pts.size(), t.size());
      for (const P& q : pts) {
        EXPECT_GE(q.x, 0);
        EXPECT_LE(q.x, W);
        EXPECT_GE(q.y, 0);
        EXPECT_LE(q.y, H);
      }
    }
    EXPECT_EQ(colours.size(), series.size()) << "series colours must differ";
    // Title, legend entries and y label are present.
    std::vector<std::string> texts;
    for (const Node* n : find_all(*panel_nodes[p], "text")) texts.push_back(n->text);
    EXPECT_NE(std::find(texts.begin(), texts.end(), panels[p].title), texts.end());
    EXPECT_NE(std::find(texts.begin(), texts.end(), panels[p].y_label), texts.end());
    for (const auto& s : panels[p].series)
      EXPECT_NE(std::find(texts.begin(), texts.end(), s.label), texts.end()) << s.label;
    // Gridlines and ticks exist.
    auto grid = children_with_class(*panel_nodes[p], "grid");
    ASSERT_EQ(grid.size(), 1u);
    EXPECT_GE(grid[0]->children.size(), 6u);
  }
  // Panels are stacked: the second lies below the first.
  auto polys0 = find_all(*panel_nodes[0], "polyline");
  auto polys1 = find_all(*panel_nodes[1], "polyline");
  double max0 = 0, min1 = 1e9;
  for (auto& q : points_of(*polys0[0])) max0 = std::max(max0, q.y);
  for (auto& q : points_of(*polys1[0])) min1 = std::min(min1, q.y);
  EXPECT_LT(max0, min1);
}

TEST(PlotSvg, TicksAreRoundNumbers) {
  auto check = [](double lo, double hi, std::vector<double> want) {
    auto got = efc::nice_ticks(lo, hi, 5);
    ASSERT_EQ(got.size(), want.size()) << lo << ".." << hi;
    for (size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], want[i], 1e-12);
  };
  check(0, 10, {0, 2, 4, 6, 8, 10});
  check(0, 1, {0, 0.2, 0.4, 0.6, 0.8, 1.0});
  check(-0.37, 1.23, {0, 0.5, 1.0});
  check(0, 3.14159, {0, 0.5, 1, 1.5, 2, 2.5, 3});
  check(1200, 1800, {1200, 1300, 1400, 1500, 1600, 1700, 1800});
  EXPECT_EQ(efc::nice_ticks(2, 2, 5).size(), 1u);
  EXPECT_TRUE(efc::nice_ticks(kNaN, 1, 5).empty());

  // Tick labels in the SVG are short round numbers.
  std::vector<double> t = time_axis(371, 0.01);  // 0 .. 3.7 s
  std::vector<double> v(t.size());
  for (size_t i = 0; i < t.size(); ++i) v[i] = 0.1234 * std::sin(t[i] * 3);
  auto root = parse_ok(efc::plot_svg(t, {{"p", "m", {{"x", v}}}}));
  ASSERT_NE(root, nullptr);
  int labels = 0;
  for (const char* cls : {"xlabels", "ylabels"}) {
    auto panel = children_with_class(*root, "panel");
    ASSERT_EQ(panel.size(), 1u);
    auto g = children_with_class(*panel[0], cls);
    ASSERT_EQ(g.size(), 1u);
    EXPECT_GE(g[0]->children.size(), 3u) << cls;
    for (const auto& c : g[0]->children) {
      ++labels;
      EXPECT_LE(c->text.size(), 5u) << c->text;
      EXPECT_NO_THROW(std::stod(c->text)) << c->text;
      EXPECT_EQ(c->text.find("e"), std::string::npos) << c->text;
    }
  }
  EXPECT_GE(labels, 6);
}

TEST(PlotSvg, TextIsEscaped) {
  const std::string nasty = "lamp <\"A&B\"> 'x' & </svg>";
  std::vector<double> t = {0, 1, 2};
  std::vector<efc::PlotPanel> panels = {
      {nasty + ": receptor knob", "a<b & \"c\"", {{nasty + ".s_R", {0, 1, 0}}}}};
  std::string svg = efc::plot_svg(t, panels);
  EXPECT_EQ(svg.find("<\"A&B\">"), std::string::npos);
  EXPECT_NE(svg.find("&lt;&quot;A&amp;B&quot;&gt;"), std::string::npos);
  auto root = parse_ok(svg);
  ASSERT_NE(root, nullptr);
  std::set<std::string> texts;
  for (const Node* n : find_all(*root, "text")) texts.insert(n->text);
  EXPECT_TRUE(texts.count(nasty + ": receptor knob"));
  EXPECT_TRUE(texts.count("a<b & \"c\""));
  EXPECT_TRUE(texts.count(nasty + ".s_R"));
  EXPECT_EQ(efc::xml_escape("a&b<c>d\"e'f"), "a&amp;b&lt;c&gt;d&quot;e&apos;f");
  EXPECT_EQ(efc::xml_escape(std::string("bell\x07")), "bell?");
}

TEST(PlotSvg, ConstantSeriesIsDrawnFlatInsideThePlot) {
  std::vector<double> t = time_axis(200, 0.05);
  for (double c : {2.5, 0.0, -1e-3, 1e6}) {
    std::vector<double> v(t.size(), c);
    auto root = parse_ok(efc::plot_svg(t, {{"const", "unit", {{"c", v}}}}));
    ASSERT_NE(root, nullptr);
    auto polys = find_all(*root, "polyline");
    ASSERT_EQ(polys.size(), 1u);
    auto pts = points_of(*polys[0]);
    ASSERT_EQ(pts.size(), t.size());
    auto frame = find_all(*root, "rect");
    const Node* axes = nullptr;
    for (const Node* r : frame)
      if (r->attr("class") == "axes") axes = r;
    ASSERT_NE(axes, nullptr);
    double top = std::stod(axes->attr("y")), bottom = top + std::stod(axes->attr("height"));
    for (const P& q : pts) {
      EXPECT_DOUBLE_EQ(q.y, pts[0].y);
      EXPECT_GT(q.y, top) << c;  // strictly inside: visible, not on the frame
      EXPECT_LT(q.y, bottom) << c;
    }
  }
}

TEST(PlotSvg, EmptyInputsDoNotCrash) {
  // No time points, empty series, no panels, no series, mismatched lengths.
  for (const std::string& svg :
       {efc::plot_svg({}, {}), efc::plot_svg({}, {{"empty", "", {{"a", {}}}}}),
        efc::plot_svg({0, 1}, {{"no series", "m", {}}}),
        efc::plot_svg({0, 1, 2}, {{"short", "m", {{"a", {1}}, {"b", {}}}}}),
        efc::plot_svg({5}, {{"one point", "m", {{"a", {3}}}}})}) {
    auto root = parse_ok(svg);
    ASSERT_NE(root, nullptr);
  }
  auto root = parse_ok(efc::plot_svg({0, 1, 2}, {{"p", "m", {{"empty", {}}, {"ok", {1, 2, 3}}}}}));
  ASSERT_NE(root, nullptr);
  auto series = children_with_class(*children_with_class(*root, "panel")[0], "series");
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(find_all(*series[0], "polyline").size(), 0u);
  EXPECT_EQ(find_all(*series[1], "polyline").size(), 1u);
}

TEST(PlotSvg, NanValuesLeaveGaps) {
  std::vector<double> t = time_axis(100, 0.1);
  std::vector<double> gappy(t.size()), all_nan(t.size(), kNaN), inf(t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    gappy[i] = (i >= 40 && i < 50) ? kNaN : std::sin(t[i]);
    inf[i] = i == 10 ? std::numeric_limits<double>::infinity() : 1.0 + t[i];
  }
  auto root = parse_ok(efc::plot_svg(
      t, {{"gaps", "m", {{"gappy", gappy}, {"nan", all_nan}, {"inf", inf}}}}));
  ASSERT_NE(root, nullptr);
  auto series = children_with_class(*children_with_class(*root, "panel")[0], "series");
  ASSERT_EQ(series.size(), 3u);
  auto gp = find_all(*series[0], "polyline");
  ASSERT_EQ(gp.size(), 2u);
  EXPECT_EQ(points_of(*gp[0]).size(), 40u);
  EXPECT_EQ(points_of(*gp[1]).size(), 50u);
  EXPECT_EQ(find_all(*series[1], "polyline").size(), 0u);
  EXPECT_EQ(find_all(*series[2], "polyline").size(), 2u);
  // NaN in time as well.
  std::vector<double> tn = t;
  tn[5] = kNaN;
  auto root2 = parse_ok(efc::plot_svg(tn, {{"t gap", "m", {{"v", inf}}}}));
  ASSERT_NE(root2, nullptr);
  EXPECT_EQ(find_all(*root2, "polyline").size(), 3u);
}

TEST(PlotSvg, DecimationBoundsPointsAndKeepsStepsAndSpikes) {
  const size_t n = 200000;
  std::vector<double> t = time_axis(n, 1e-4);  // 20 s
  std::vector<double> step(n), spike(n, 0.0), noisy(n);
  for (size_t i = 0; i < n; ++i) {
    step[i] = t[i] < 7.0 ? 0.0 : 1.0;
    noisy[i] = std::sin(t[i]) + ((i * 7919) % 13) * 0.01;
  }
  spike[123457] = 5.0;  // one sample
  auto root = parse_ok(efc::plot_svg(t, {{"step", "m", {{"step", step}}},
                                         {"spike", "m", {{"spike", spike}}},
                                         {"noisy", "m", {{"noisy", noisy}}}}));
  ASSERT_NE(root, nullptr);
  std::vector<const Node*> series;
  for (const Node* panel : children_with_class(*root, "panel"))
    for (const Node* s : children_with_class(*panel, "series")) series.push_back(s);
  ASSERT_EQ(series.size(), 3u);
  std::vector<std::vector<P>> pts;
  for (const Node* s : series) {
    auto polys = find_all(*s, "polyline");
    ASSERT_EQ(polys.size(), 1u);
    pts.push_back(points_of(*polys[0]));
    EXPECT_LE(pts.back().size(), size_t(efc::kPlotMaxPointsPerSeries));
    EXPECT_GE(pts.back().size(), 100u);
    for (size_t k = 1; k < pts.back().size(); ++k)
      EXPECT_GE(pts.back()[k].x, pts.back()[k - 1].x) << "points in time order";
  }
  // The step stays a step: some consecutive pair within one pixel jumps the full height.
  double ymin = 1e9, ymax = -1e9;
  for (const P& q : pts[0]) ymin = std::min(ymin, q.y), ymax = std::max(ymax, q.y);
  EXPECT_GT(ymax - ymin, 100);
  bool vertical = false;
  for (size_t k = 1; k < pts[0].size(); ++k)
    if (std::fabs(pts[0][k].x - pts[0][k - 1].x) < 1.5 &&
        std::fabs(pts[0][k].y - pts[0][k - 1].y) > 0.9 * (ymax - ymin))
      vertical = true;
  EXPECT_TRUE(vertical);
  // The one-sample spike survives.
  double smin = 1e9, smax = -1e9;
  for (const P& q : pts[1]) smin = std::min(smin, q.y), smax = std::max(smax, q.y);
  EXPECT_GT(smax - smin, 100);

  // Decimated series with a NaN gap: still split, still bounded.
  std::vector<double> gappy = noisy;
  for (size_t i = 50000; i < 60000; ++i) gappy[i] = kNaN;
  auto root2 = parse_ok(efc::plot_svg(t, {{"big gap", "m", {{"g", gappy}}}}));
  ASSERT_NE(root2, nullptr);
  auto polys = find_all(*root2, "polyline");
  ASSERT_EQ(polys.size(), 2u);
  size_t total = points_of(*polys[0]).size() + points_of(*polys[1]).size();
  EXPECT_LE(total, size_t(efc::kPlotMaxPointsPerSeries));
}

TEST(PlotSvg, ManySeriesStayDistinguishable) {
  std::vector<double> t = {0, 1};
  efc::PlotPanel p{"many", "m", {}};
  for (int i = 0; i < 14; ++i) p.series.push_back({"s" + std::to_string(i), {double(i), i + 1.0}});
  auto root = parse_ok(efc::plot_svg(t, {p}));
  ASSERT_NE(root, nullptr);
  auto series = children_with_class(*children_with_class(*root, "panel")[0], "series");
  ASSERT_EQ(series.size(), 14u);
  std::set<std::string> styles;
  for (const Node* s : series) styles.insert(s->attr("stroke") + "|" + s->attr("stroke-dasharray"));
  EXPECT_EQ(styles.size(), 14u);
  auto legend = children_with_class(*children_with_class(*root, "panel")[0], "legend");
  ASSERT_EQ(legend.size(), 1u);
  EXPECT_EQ(find_all(*legend[0], "text").size(), 14u);
}

TEST(PlotSvg, WritesFileAndReportsIoErrors) {
  std::vector<double> t = {0, 0.5, 1};
  std::vector<efc::PlotPanel> panels = {{"f: receptor r", "rad", {{"f.s_R", {0, 0.2, 0.4}}}}};
  std::string path = testing::TempDir() + "efc_plot_test.svg";
  std::string err;
  ASSERT_TRUE(efc::write_plot_svg(path, t, panels, &err)) << err;
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_EQ(ss.str(), efc::plot_svg(t, panels));
  if (const char* keep = std::getenv("EFC_KEEP_PLOT")) {
    std::ofstream out(keep);
    out << ss.str();
  }
  std::remove(path.c_str());
  err.clear();
  EXPECT_FALSE(efc::write_plot_svg("/nonexistent_dir_efc/x/plot.svg", t, panels, &err));
  EXPECT_FALSE(err.empty());
  EXPECT_FALSE(efc::write_plot_svg("/nonexistent_dir_efc/x/plot.svg", t, panels, nullptr));
}

}  // namespace
