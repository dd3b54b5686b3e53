// Axis-aligned bounds of spec GEOMETRY values, read straight from the JSON
// (the suite links no geometry library). Used to tell small receptors and to
// keep scaled examples in a realistic size range, so a box with an `rpy` is
// bounded by its circumscribed sphere: exact enough, and free of sin/cos
// (whose last bits vary between platforms; the plan must not).
#pragma once

#include <limits>
#include <string>

#include "synth/suite/spec_json.h"

namespace efc::synth::suite {

struct Bounds {
  V3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::infinity()};
  V3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity()};

  bool empty() const { return !(lo[0] <= hi[0]); }
  void add_point(const V3& p);
  double max_extent() const;  // 0 when empty
};

// Adds a GEOMETRY's bounds (object frame, every joint at 0) to *out. Meshes
// are read relative to base_dir (OBJ `v` lines, times `scale`). False with
// *error when a mesh cannot be read or the value is not a geometry.
bool add_geometry_bounds(const SpecJson& geometry, const std::string& base_dir, Bounds* out,
                         std::string* error);

}  // namespace efc::synth::suite
