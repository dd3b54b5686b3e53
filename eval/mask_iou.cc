#include "eval/mask_iou.h"

#include <algorithm>
#include <filesystem>


namespace efc::eval {

double mask_iou(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  size_t both = 0, either = 0;
  const size_t n = std::min(a.size(), b.size());
  for (size_t i = 0; i < n; ++i) {
    both += a[i] && b[i];
    either += a[i] || b[i];
  }
  return either == 0 ? 1.0 : static_cast<double>(both) / static_cast<double>(either);
}

bool score_part_masks(const seq::Sequence& truth, const std::string& gt_part, const std::string& pred_dir,
                      const std::string& pred_part, Diagnostics& diags, bool* has_truth, MaskScore* out) {
  *has_truth = false;
  const auto& names = truth.mask_names();
  if (std::find(names.begin(), names.end(), gt_part) == names.end()) return true;
  *has_truth = true;
  const int frames = truth.meta().frames;
  double sum = 0;
  for (int f = 0; f < frames; ++f) {
    seq::Image8 gt;
    if (!truth.read_mask(gt_part, f, diags, &gt)) return false;
    std::vector<uint8_t> pred(gt.pixels.size(), 0);
    const std::string pred_path = pred_dir + "/masks/" + pred_part + "/" + seq::frame_file(f);
    std::error_code ec;
    if (!pred_part.empty() && std::filesystem::exists(pred_path, ec)) {
      seq::Image8 img;
      std::string error;
      if (!seq::read_png_gray8(pred_path, &img, &error)) {
        diags.error("E1023", pred_path, 0, 0, "", "the file " + error);
        return false;
      }
      if (img.width != gt.width || img.height != gt.height) {
        diags.error("E1023", pred_path, 0, 0, "",
                    "predicted mask is " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                        ", the true one " + std::to_string(gt.width) + "x" + std::to_string(gt.height));
        return false;
      }
      pred = std::move(img.pixels);
    }
    sum += mask_iou(pred, gt.pixels);
  }
  out->part = gt_part;
  out->mean_iou = frames > 0 ? sum / frames : 1.0;
  return true;
}

}  // namespace efc::eval
