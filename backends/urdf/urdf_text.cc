// The URDF target's rpy (numbers and escaping are in backends/common/text.h).
#include <algorithm>
#include <cmath>

#include "backends/urdf/urdf_backend.h"

namespace efc {
namespace urdf {

Vec3 matrix_to_rpy(const Mat3& R) {
  // R = Rz(yaw) Ry(pitch) Rx(roll): R[2][0] = -sin(pitch).
  const double sp = std::max(-1.0, std::min(1.0, -R[2][0]));
  const double pitch = std::asin(sp);
  if (std::fabs(sp) < 1 - 1e-12) {
    return {std::atan2(R[2][1], R[2][2]), pitch, std::atan2(R[1][0], R[0][0])};
  }
  // Gimbal lock: only roll -/+ yaw is defined; put it all in yaw.
  return {0.0, pitch, std::atan2(-R[0][1], R[1][1])};
}

}  // namespace urdf
}  // namespace efc
