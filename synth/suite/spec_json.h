// Small helpers for writing spec documents: an ordered JSON (keys stay in the
// order a person writes them: name, role, geometry, ...), 3-vectors, and
// numbers snapped to a decimal grid.
#pragma once

#include <array>
#include <cmath>

#include <nlohmann/json.hpp>

namespace efc::synth::suite {

using SpecJson = nlohmann::ordered_json;
using V3 = std::array<double, 3>;

// x rounded to a multiple of 1/per (per a power of ten). The written number is
// then a short decimal, and no platform-dependent last bit survives into the
// document. `+ 0.0` turns -0 into 0.
inline double snap(double x, double per = 1e6) { return std::round(x * per) / per + 0.0; }

inline SpecJson json_vec(const V3& v, double per = 1e6) {
  return SpecJson::array({snap(v[0], per), snap(v[1], per), snap(v[2], per)});
}

inline V3 add(const V3& a, const V3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline V3 scale(const V3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline V3 unit(const V3& a) {
  const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  return {a[0] / n, a[1] / n, a[2] / n};
}

// Reads [x, y, z] when `j` is an array of three numbers.
inline bool read_vec(const SpecJson& j, V3* out) {
  if (!j.is_array() || j.size() != 3) return false;
  for (size_t k = 0; k < 3; ++k) {
    if (!j[k].is_number()) return false;
    (*out)[k] = j[k].get<double>();
  }
  return true;
}

}  // namespace efc::synth::suite
