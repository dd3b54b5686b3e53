// The spec's formula for s_E (shared/spec/efc-spec-v1.md), written from the
// spec's text rather than with the runtime, so tests of every target check
// the logged s_E against the same independent definition.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "compiler/core/resolve.h"
#include "compiler/ir.h"

namespace efc_test {

using namespace efc;

inline double clamp_between(double v, double a, double b) {
  return std::min(std::max(v, std::min(a, b)), std::max(a, b));
}

// s_E for every row from the logged s_R series, straight from the spec:
// binary s_E = e_hi while s_R >= t; latching: each press toggles; step: on once
// s_R > t, off once s_R < t - h; linear: clamp(b + C (s_R - r_lo)); cumulative:
// each press adds d, clamped. A press is an upward crossing of t after s_R was
// below t - 1% of the receptor range (the runtime's documented debounce).
inline std::vector<double> spec_formula(const Object& obj, const Function& f, const std::vector<double>& s_r) {
  double r_lo, r_hi;
  receptor_range(obj, f, &r_lo, &r_hi);
  const Mapping& m = f.mapping;
  const double e_lo = f.effect.lo, e_hi = f.effect.hi;
  const double band = 0.01 * (r_hi - r_lo);
  std::vector<double> out;
  bool on = false, armed = false;
  double acc = m.type == MappingType::Cumulative ? clamp_between(*m.initial, e_lo, e_hi) : 0;
  for (size_t i = 0; i < s_r.size(); ++i) {
    const double s = s_r[i];
    bool press = false;
    if (m.type == MappingType::Cumulative || (m.type == MappingType::Binary && *m.latching)) {
      if (i == 0) {
        armed = s < *m.threshold - band;
      } else if (!armed) {
        armed = s < *m.threshold - band;
      } else if (s >= *m.threshold) {
        press = true;
        armed = false;
      }
    }
    switch (m.type) {
      case MappingType::Binary:
        if (*m.latching) {
          if (press) on = !on;
        } else {
          on = s >= *m.threshold;
        }
        out.push_back(on ? e_hi : e_lo);
        break;
      case MappingType::Step:
        if (i == 0) on = s > *m.threshold;
        else if (!on && s > *m.threshold) on = true;
        else if (on && s < *m.threshold - *m.hysteresis) on = false;
        out.push_back(on ? e_hi : e_lo);
        break;
      case MappingType::Linear:
        out.push_back(clamp_between(*m.offset + *m.gain * (s - r_lo), e_lo, e_hi));
        break;
      case MappingType::Cumulative:
        if (press) acc = clamp_between(acc + *m.delta, e_lo, e_hi);
        out.push_back(acc);
        break;
    }
  }
  return out;
}

}  // namespace efc_test
