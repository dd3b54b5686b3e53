// camera_intrinsics_path: {"undistorted_intrinsics": 3x3, "original_frame_size":
// [W, H]} and, for EgoExo4D crops, "cropped_intrinsics" (3x3, for the
// cropped frames), "cropped_top_left" and "cropped_bottom_right" ([x, y]
// pixels of the original frame; the bottom-right corner is exclusive, as
// the reference loader slices masks[:, y0:y1, x0:x1]).
#pragma once

#include <string>

#include "pipeline/egofun3d/json_doc.h"
#include "sequence/sequence.h"

namespace efc::egofun3d {

struct CameraIntrinsics {
  seq::Intrinsics k;          // for the frames the sequence stores
  int original_width = 0, original_height = 0;
  bool cropped = false;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the stored frames' box in the original frame
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

// `use_crop`: the video is the cropped one, so the crop keys are required.
// E1043 errors at their line:col; false after any. *doc keeps the file for
// later located errors (a video of another size).
bool read_intrinsics(const std::string& path, bool use_crop, Diagnostics& diags, JsonDoc* doc,
                     CameraIntrinsics* out);

}  // namespace efc::egofun3d
