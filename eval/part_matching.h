// Which predicted part stands for which true part: by name first; a true part
// left over then takes a left-over predicted part of the same role (receptor,
// effector, base, other), the one whose world bounding-box centre is nearest
// when several qualify. True parts are served in spec order.
#pragma once

#include <vector>

#include "compiler/ir.h"
#include "eval/world_frame.h"

namespace efc::eval {

// For every part of gt, the index of its predicted part in pred, or -1.
std::vector<int> match_parts(const Object& gt, const WorldFrame& gt_world, const Object& pred,
                             const WorldFrame& pred_world);

}  // namespace efc::eval
