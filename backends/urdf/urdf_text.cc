// Text helpers of the URDF target: numbers, comments, rpy.
#include <charconv>
#include <cmath>

#include "backends/urdf/urdf_backend.h"

namespace efc {
namespace urdf {

std::string num(double v) {
  if (v == 0) return "0";  // also turns -0 into 0
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string vec(const Vec3& v) { return num(v[0]) + " " + num(v[1]) + " " + num(v[2]); }

std::string comment_text(const std::string& s) {
  // XML comments may not contain "--" nor end with "-"; control characters
  // (but tab and newline) are not XML 1.0 characters at all.
  std::string out;
  for (char c : s) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 && c != '\n' && c != '\t') {
      out += ' ';
    } else if (c == '-' && !out.empty() && out.back() == '-') {
      out += " -";
    } else {
      out += c;
    }
  }
  if (!out.empty() && out.back() == '-') out += ' ';
  return out;
}

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
