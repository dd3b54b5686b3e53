// Mask IoU, the paper's segmentation metric: per frame |A n B| / |A u B|
// (an empty union scores 1: both agree the part is not in view), averaged
// over every frame; a part succeeds at a mean of at least 0.5.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "sequence/sequence.h"

namespace efc::eval {

constexpr double kMaskSuccessIoU = 0.5;

// IoU of two masks of the same size (non-zero = inside).
double mask_iou(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

struct MaskScore {
  std::string part;  // the true part's name
  double mean_iou = 0;
  bool success() const { return mean_iou >= kMaskSuccessIoU; }
};

// The true masks of `gt_part` in the sequence (SEQ/masks/<gt_part>/, one per
// frame of meta.json) against the predicted ones in
// pred_dir/masks/<pred_part>/NNNNNN.png. A predicted frame that is missing
// (or pred_part empty: no predicted part) is an empty mask: nothing found.
// False, with a located error, when a file cannot be read or is of another
// size than the true frame (E1023).
// `has_truth` is false (and *out untouched) when the sequence has no masks
// for gt_part.
bool score_part_masks(const seq::Sequence& truth, const std::string& gt_part, const std::string& pred_dir,
                      const std::string& pred_part, Diagnostics& diags, bool* has_truth, MaskScore* out);

}  // namespace efc::eval
