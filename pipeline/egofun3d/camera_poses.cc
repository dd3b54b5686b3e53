#include "pipeline/egofun3d/camera_poses.h"

#include <cmath>

namespace efc::egofun3d {

bool matrices_to_poses(const std::vector<Matrix4>& ms, double fps, std::vector<seq::Pose>* out, std::string* error) {
  out->clear();
  for (size_t i = 0; i < ms.size(); ++i) {
    const Matrix4& m = ms[i];
    auto R = [&](int r, int c) { return m[r * 4 + c]; };
    double worst = std::fabs(m[12]) + std::fabs(m[13]) + std::fabs(m[14]) + std::fabs(m[15] - 1);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        double dot = 0;
        for (int k = 0; k < 3; ++k) dot += R(k, a) * R(k, b);
        worst = std::max(worst, std::fabs(dot - (a == b ? 1.0 : 0.0)));
      }
    const double det = R(0, 0) * (R(1, 1) * R(2, 2) - R(1, 2) * R(2, 1)) -
                       R(0, 1) * (R(1, 0) * R(2, 2) - R(1, 2) * R(2, 0)) +
                       R(0, 2) * (R(1, 0) * R(2, 1) - R(1, 1) * R(2, 0));
    if (worst > 1e-3 || det < 0) {
      *error = "matrix " + std::to_string(i) +
               " is not a rigid camera-to-world transform (its 3x3 part is not a rotation, or the last row is not "
               "0 0 0 1)";
      return false;
    }
    // Shepperd's method: the largest of w, x, y, z first, for accuracy.
    double q[4];  // x y z w
    const double tr = R(0, 0) + R(1, 1) + R(2, 2);
    if (tr > 0) {
      const double s = std::sqrt(tr + 1) * 2;
      q[3] = s / 4;
      q[0] = (R(2, 1) - R(1, 2)) / s;
      q[1] = (R(0, 2) - R(2, 0)) / s;
      q[2] = (R(1, 0) - R(0, 1)) / s;
    } else if (R(0, 0) > R(1, 1) && R(0, 0) > R(2, 2)) {
      const double s = std::sqrt(1 + R(0, 0) - R(1, 1) - R(2, 2)) * 2;
      q[3] = (R(2, 1) - R(1, 2)) / s;
      q[0] = s / 4;
      q[1] = (R(0, 1) + R(1, 0)) / s;
      q[2] = (R(0, 2) + R(2, 0)) / s;
    } else if (R(1, 1) > R(2, 2)) {
      const double s = std::sqrt(1 + R(1, 1) - R(0, 0) - R(2, 2)) * 2;
      q[3] = (R(0, 2) - R(2, 0)) / s;
      q[0] = (R(0, 1) + R(1, 0)) / s;
      q[1] = s / 4;
      q[2] = (R(1, 2) + R(2, 1)) / s;
    } else {
      const double s = std::sqrt(1 + R(2, 2) - R(0, 0) - R(1, 1)) * 2;
      q[3] = (R(1, 0) - R(0, 1)) / s;
      q[0] = (R(0, 2) + R(2, 0)) / s;
      q[1] = (R(1, 2) + R(2, 1)) / s;
      q[2] = s / 4;
    }
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    seq::Pose p;
    p.t = static_cast<double>(i) / fps;
    p.p = {R(0, 3), R(1, 3), R(2, 3)};
    p.q = {q[0] / n, q[1] / n, q[2] / n, q[3] / n};
    out->push_back(p);
  }
  return true;
}

}  // namespace efc::egofun3d
