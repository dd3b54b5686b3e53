// geometry_path: the object's geometry as a PLY file (a mesh or a point
// cloud, in the world frame of the camera extrinsics). Only what the
// importer needs is kept: vertex x y z and, when there is a face element,
// its vertex_indices (or vertex_index) lists. ascii and
// binary_little_endian; every other element and property is skipped.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"

namespace efc::egofun3d {

struct Ply {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::vector<int>> faces;  // polygons; indices checked < vertices.size()
};

// False after an E1045 error at file:line (header and ascii body lines; the
// binary body has no lines, its errors name the element and item).
bool read_ply(const std::string& path, Diagnostics& diags, Ply* out);

}  // namespace efc::egofun3d
