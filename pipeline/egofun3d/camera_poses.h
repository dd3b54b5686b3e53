// extrinsics.npy matrices (camera-to-world, OpenCV camera axes, as
// poses.txt wants them) to TUM poses: t = i / fps, the translation column,
// and the rotation as a unit quaternion x y z w.
#pragma once

#include <string>
#include <vector>

#include "pipeline/egofun3d/npy.h"
#include "sequence/sequence.h"

namespace efc::egofun3d {

// False with *error naming the first matrix that is not a rigid transform
// (rotation part not orthonormal with determinant +1 within 1e-3, or a last
// row other than 0 0 0 1).
bool matrices_to_poses(const std::vector<Matrix4>& m, double fps, std::vector<seq::Pose>* out, std::string* error);

}  // namespace efc::egofun3d
