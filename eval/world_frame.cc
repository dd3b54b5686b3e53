#include "eval/world_frame.h"

#include <cmath>

#include "compiler/frontend/check.h"
#include "compiler/geometry/vec.h"

namespace efc::eval {

namespace {
constexpr const char* kKey = "x-efc-object-to-world";
}

Vec3 WorldFrame::point(const Vec3& p) const { return geom::add(geom::apply(rotation, p), translation); }

Vec3 WorldFrame::direction(const Vec3& d) const { return geom::normalized(geom::apply(rotation, d)); }

bool read_transform(const nlohmann::json& v, const std::string& subject, WorldFrame* out, std::string* problem,
                    std::string* pointer_suffix) {
  *out = WorldFrame{};
  pointer_suffix->clear();
  if (!v.is_array() || v.size() != 16) {
    *problem = subject + " must be an array of 16 numbers";
    return false;
  }
  double m[16];
  for (int i = 0; i < 16; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>())) {
      *problem = subject + " element " + std::to_string(i) + " is not a finite number";
      *pointer_suffix = "/" + std::to_string(i);
      return false;
    }
    m[i] = v[i].get<double>();
  }
  if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1) {
    *problem = subject + " last row is not 0 0 0 1";
    *pointer_suffix = "/12";
    return false;
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out->rotation[r][c] = m[4 * r + c];
    out->translation[r] = m[4 * r + 3];
  }
  const Mat3& a = out->rotation;
  const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                     a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                     a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  if (std::fabs(det) < 1e-12) {
    *problem = subject + " is singular (its 3x3 part has no inverse)";
    *out = WorldFrame{};
    return false;
  }
  return true;
}

bool object_to_world(const Object& obj, Diagnostics& diags, WorldFrame* out) {
  *out = WorldFrame{};
  const auto it = obj.extensions.find(kKey);
  if (it == obj.extensions.end()) return true;
  std::string problem, suffix;
  if (read_transform(it->second, std::string("'") + kKey + "'", out, &problem, &suffix)) return true;
  report(diags, obj, "E1020", std::string("/") + kKey + suffix, problem,
         "write 16 numbers, row-major, last row [0, 0, 0, 1]");
  return false;
}

}  // namespace efc::eval
