// camera_extrinsics_path: a NumPy .npy file holding an (N, 4, 4) array of
// camera-to-world matrices (OpenCV camera axes). Parsed here rather than
// through a library: the format is a magic string, a version, a Python-dict
// header and raw little-endian numbers, and only one shape is accepted.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"

namespace efc::egofun3d {

using Matrix4 = std::array<double, 16>;  // row-major

// Accepts versions 1.0, 2.0 and 3.0, dtype '<f8' or '<f4' (also '<d', '<f'),
// fortran_order False, shape (N, 4, 4) with N >= 1; values must be finite.
// Anything else is an E1042 error at the file (line 1, the column of the
// header field that is wrong). False after any error.
bool read_npy_matrices(const std::string& path, Diagnostics& diags, std::vector<Matrix4>* out);

}  // namespace efc::egofun3d
