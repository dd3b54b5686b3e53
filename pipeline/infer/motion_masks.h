// efc infer without any masks: a fallback that finds what moves. Each
// frame's depth is compared with the frames five before and after, through
// the camera poses: a point that now lies in front of where the other frame
// saw the surface along the same ray has moved into view (a part turning, a
// door opening, the hand). Those points are the part "moving" (role
// receptor); the still points around them (within kRegionRadius of the
// median moving point) are the body "body" (role object). It cannot name
// parts or tell the hand from what it holds, so it is a last resort, used
// with a warning (E1053): an external segmenter's masks are far better.
#pragma once

#include "pipeline/infer/observations.h"

namespace efc::pipeline {

constexpr double kRegionRadius = 0.6;  // m

// Fills out->parts (and sets out->motion_masks) from depth and poses alone;
// out->times and out->camera_to_world must be filled. False after an error
// (a frame that cannot be read).
bool observe_by_motion(const seq::Sequence& sequence, const ObserveOptions& options, Diagnostics& diags,
                       const ProgressFn& progress, Observations* out);

}  // namespace efc::pipeline
