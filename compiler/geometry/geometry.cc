// Rotations used by primitives: roll-pitch-yaw (boxes) and z-to-axis
// (cylinders).
#include "compiler/geometry/geometry.h"

#include <cmath>

#include "compiler/geometry/vec.h"

namespace efc {

using namespace geom;

Mat3 rpy_to_matrix(const Vec3& rpy) {
  // URDF: fixed-axis rotations about x (roll), then y (pitch), then z (yaw),
  // so R = Rz(yaw) * Ry(pitch) * Rx(roll).
  const double cr = std::cos(rpy[0]), sr = std::sin(rpy[0]);
  const double cp = std::cos(rpy[1]), sp = std::sin(rpy[1]);
  const double cy = std::cos(rpy[2]), sy = std::sin(rpy[2]);
  return Mat3{{{cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr},
               {sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr},
               {-sp, cp * sr, cp * cr}}};
}

Mat3 rotation_z_to(const Vec3& axis) {
  // The smallest rotation taking +z onto the axis (Rodrigues). Around the two
  // poles the cross product vanishes: +z needs nothing, -z a half turn about
  // x (any perpendicular axis would do; x keeps the result deterministic).
  const Vec3 a = normalized(axis);
  if (norm(a) == 0) return identity();
  const Vec3 z{0, 0, 1};
  const Vec3 v = cross(z, a);  // sin(theta) * unit rotation axis
  const double c = dot(z, a);  // cos(theta)
  const double s = norm(v);
  if (s < 1e-12) {
    if (c > 0) return identity();
    return Mat3{{{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}};
  }
  // R = I + [v]x + [v]x^2 (1 - c) / s^2
  const Mat3 vx{{{0, -v[2], v[1]}, {v[2], 0, -v[0]}, {-v[1], v[0], 0}}};
  const Mat3 vx2 = matmul(vx, vx);
  const double k = (1 - c) / (s * s);
  Mat3 r = identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i][j] += vx[i][j] + vx2[i][j] * k;
  return r;
}

}  // namespace efc
