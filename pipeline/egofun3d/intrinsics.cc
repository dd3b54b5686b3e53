#include "pipeline/egofun3d/intrinsics.h"

#include <cmath>

namespace efc::egofun3d {
namespace {

constexpr const char* kCode = "E1043";

// fx 0 cx / 0 fy cy / 0 0 1 (OpenCV). A skew or a last row other than
// 0 0 1 cannot be expressed in meta.json's four numbers.
bool to_intrinsics(const JsonDoc& doc, Diagnostics& diags, const std::string& key, const std::array<double, 9>& m,
                   seq::Intrinsics* out) {
  const bool pinhole = std::fabs(m[1]) < 1e-9 && std::fabs(m[3]) < 1e-9 && std::fabs(m[6]) < 1e-9 &&
                       std::fabs(m[7]) < 1e-9 && std::fabs(m[8] - 1) < 1e-9;
  if (!pinhole || !(m[0] > 0) || !(m[4] > 0)) {
    doc.error(diags, kCode, pointer_join("", key),
              "\"" + key + "\" is not a pinhole camera matrix [[fx, 0, cx], [0, fy, cy], [0, 0, 1]] with fx, fy > 0");
    return false;
  }
  *out = {m[0], m[4], m[2], m[5]};
  return true;
}

bool integers(const JsonDoc& doc, Diagnostics& diags, const std::string& key, int* a, int* b) {
  auto v = doc.numbers(diags, kCode, "", key, 2);
  if (!v) return false;
  if ((*v)[0] != std::floor((*v)[0]) || (*v)[1] != std::floor((*v)[1]) || (*v)[0] < 0 || (*v)[1] < 0 ||
      (*v)[0] > 1e6 || (*v)[1] > 1e6) {
    doc.error(diags, kCode, pointer_join("", key), "\"" + key + "\" must be two non-negative integers (pixels)");
    return false;
  }
  *a = static_cast<int>((*v)[0]);
  *b = static_cast<int>((*v)[1]);
  return true;
}

}  // namespace

bool read_intrinsics(const std::string& path, bool use_crop, Diagnostics& diags, JsonDoc* doc,
                     CameraIntrinsics* out) {
  *out = CameraIntrinsics{};
  if (!doc->read(path, kCode, diags)) return false;
  const size_t before = diags.error_count();
  if (!doc->root().is_object()) {
    doc->error(diags, kCode, "", "the intrinsics file must be a JSON object");
    return false;
  }
  integers(*doc, diags, "original_frame_size", &out->original_width, &out->original_height);
  if (diags.error_count() == before && (out->original_width == 0 || out->original_height == 0))
    doc->error(diags, kCode, "/original_frame_size", "\"original_frame_size\" must be positive [W, H]");
  const bool has_crop = doc->root().contains("cropped_intrinsics");
  if (use_crop && !has_crop)
    doc->error(diags, kCode, "", "the entry names a cropped video but this file has no \"cropped_intrinsics\"",
               "give cropped_intrinsics, cropped_top_left and cropped_bottom_right, or use the original video");
  if (use_crop && has_crop) {
    out->cropped = true;
    if (auto m = doc->matrix3(diags, kCode, "", "cropped_intrinsics"))
      to_intrinsics(*doc, diags, "cropped_intrinsics", *m, &out->k);
    const size_t box_errors = diags.error_count();
    integers(*doc, diags, "cropped_top_left", &out->x0, &out->y0);
    integers(*doc, diags, "cropped_bottom_right", &out->x1, &out->y1);
    if (diags.error_count() == box_errors && diags.error_count() == before &&
        (out->x1 <= out->x0 || out->y1 <= out->y0 || out->x1 > out->original_width ||
         out->y1 > out->original_height))
      doc->error(diags, kCode, "/cropped_bottom_right",
                 "the crop box [" + std::to_string(out->x0) + ", " + std::to_string(out->y0) + "] .. [" +
                     std::to_string(out->x1) + ", " + std::to_string(out->y1) +
                     ") is empty or leaves the original frame of " + std::to_string(out->original_width) + "x" +
                     std::to_string(out->original_height));
  } else if (!use_crop) {
    if (auto m = doc->matrix3(diags, kCode, "", "undistorted_intrinsics"))
      to_intrinsics(*doc, diags, "undistorted_intrinsics", *m, &out->k);
    out->x1 = out->original_width;
    out->y1 = out->original_height;
  }
  return diags.error_count() == before;
}

}  // namespace efc::egofun3d
