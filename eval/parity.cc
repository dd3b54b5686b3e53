#include "eval/parity.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "backends/common/lowering.h"

namespace efc {
namespace {

// Index of the first row of the run of equal values that ends at row i.
std::vector<size_t> hold_start(const std::vector<double>& v) {
  std::vector<size_t> out(v.size(), 0);
  for (size_t i = 1; i < v.size(); ++i) out[i] = v[i] == v[i - 1] ? out[i - 1] : i;
  return out;
}

std::vector<size_t> transitions(const std::vector<double>& v) {
  std::vector<size_t> out;
  for (size_t i = 1; i < v.size(); ++i)
    if (v[i] != v[i - 1]) out.push_back(i);
  return out;
}

std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

std::vector<FunctionParity> compare_logs(const Object& obj, const SimLog& a, const SimLog& b, double dt,
                                         std::string* error) {
  std::vector<FunctionParity> out;
  if (a.columns != b.columns || a.rows.size() != b.rows.size()) {
    *error = "the logs have other columns or rows (" + std::to_string(b.columns.size()) + " columns x " +
             std::to_string(b.rows.size()) + " rows, want " + std::to_string(a.columns.size()) + " x " +
             std::to_string(a.rows.size()) + ")";
    return out;
  }
  std::set<int> geometry_effectors;
  for (const Function& f : obj.functions)
    if (f.effect.type == EffectType::Geometry) geometry_effectors.insert(lowering::effector_part(obj, f));

  const size_t hold_rows = static_cast<size_t>(std::lround(kSteadyHold / dt));
  for (size_t c = 1; c + 2 < a.columns.size(); c += 3) {
    const std::string fname = a.columns[c].substr(0, a.columns[c].size() - 4);
    const Function* f = nullptr;
    for (const Function& g : obj.functions)
      if (g.name == fname) f = &g;
    if (!f) continue;
    FunctionParity p;
    p.function = fname;
    p.effect = f->effect.type;
    p.chained = geometry_effectors.count(lowering::receptor_part(obj, *f)) > 0;
    std::vector<double> me, be;
    for (size_t r = 0; r < b.rows.size(); ++r) {
      const auto& x = a.rows[r];
      const auto& y = b.rows[r];
      me.push_back(x[c + 1]);
      be.push_back(y[c + 1]);
      p.max_ds_r = std::max(p.max_ds_r, std::fabs(x[c] - y[c]));
      const double dse = std::fabs(x[c + 1] - y[c + 1]);
      p.max_ds_e = std::max(p.max_ds_e, dse);
      p.max_dmeasured = std::max(p.max_dmeasured, std::fabs(x[c + 2] - y[c + 2]));
      if (!p.chained && dse > kSETolerance * (1 + std::fabs(x[c + 1]))) p.se_ok = false;
    }
    const std::vector<size_t> hm = hold_start(me), hb = hold_start(be);
    if (p.chained) {
      const std::vector<size_t> tm = transitions(me), tb = transitions(be);
      if (tm.size() != tb.size()) {
        p.se_ok = false;
        p.note = " (" + std::to_string(tm.size()) + " vs " + std::to_string(tb.size()) + " switches)";
      } else {
        size_t shift = 0;
        for (size_t i = 0; i < tm.size(); ++i) shift = std::max(shift, tm[i] > tb[i] ? tm[i] - tb[i] : tb[i] - tm[i]);
        p.note = " (chained: switches shifted <= " + short_number(shift * dt) + " s)";
        if (shift * dt > kChainShift + 1e-12) p.se_ok = false;
      }
      for (size_t r = 0; r < me.size(); ++r)
        if (r - hm[r] >= hold_rows && r - hb[r] >= hold_rows &&
            std::fabs(me[r] - be[r]) > kSETolerance * (1 + std::fabs(me[r])))
          p.se_ok = false;
    }
    if (f->effect.type == EffectType::Geometry) {
      const double span = std::fabs(f->effect.hi - f->effect.lo);
      p.steady_fraction = 0;
      for (size_t r = 0; r < me.size(); ++r)
        if (r - hm[r] >= hold_rows)
          p.steady_fraction = std::max(p.steady_fraction, std::fabs(a.rows[r][c + 2] - b.rows[r][c + 2]) / span);
      p.measured_ok = p.steady_fraction <= kGeometryTolerance;
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace efc
