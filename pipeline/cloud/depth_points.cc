#include "pipeline/cloud/depth_points.h"

#include <algorithm>
#include <cmath>

namespace efc::pipeline {

namespace {

// The accepted depth (metres) at (u,v), or 0 for none / out of range / outside.
double depth_at(const seq::Image16& depth, double scale, double lo, double hi, int u, int v) {
  if (u < 0 || v < 0 || u >= depth.width || v >= depth.height) return 0;
  const uint16_t raw = depth.pixels[static_cast<size_t>(v) * depth.width + u];
  if (raw == 0) return 0;
  const double z = raw * scale;
  return (z >= lo && z <= hi) ? z : 0;
}

Eigen::Vector3d unproject(const seq::Intrinsics& K, double u, double v, double z) {
  return {(u - K.cx) * z / K.fx, (v - K.cy) * z / K.fy, z};
}

}  // namespace

Cloud backproject(const seq::Image16& depth, double depth_scale, const seq::Intrinsics& K,
                  const seq::Image8* mask, const BackprojectOptions& options) {
  Cloud out;
  if (depth.width <= 0 || depth.height <= 0) return out;
  const size_t n = static_cast<size_t>(depth.width) * depth.height;
  if (depth.pixels.size() != n) return out;
  if (mask != nullptr &&
      (mask->width != depth.width || mask->height != depth.height || mask->pixels.size() != n))
    return out;  // also rejects an RGB "mask": 3 bytes a pixel
  if (!(K.fx > 0) || !(K.fy > 0) || !std::isfinite(K.fx) || !std::isfinite(K.fy) ||
      !std::isfinite(K.cx) || !std::isfinite(K.cy))
    return out;
  if (!(depth_scale > 0) || !std::isfinite(depth_scale)) return out;

  const int s = std::max(1, options.stride);
  const double lo = options.min_depth, hi = options.max_depth;
  const bool jump_test = options.max_jump_rel > 0;
  auto at = [&](int u, int v) { return depth_at(depth, depth_scale, lo, hi, u, v); };

  for (int v = 0; v < depth.height; v += s) {
    for (int u = 0; u < depth.width; u += s) {
      if (mask != nullptr && mask->pixels[static_cast<size_t>(v) * depth.width + u] == 0) continue;
      const double z = at(u, v);
      if (z == 0) continue;
      // Neighbours: left, right, up, down at +/- stride.
      const int nu[4] = {u - s, u + s, u, u};
      const int nv[4] = {v, v, v - s, v + s};
      double nz[4];
      bool keep = true;
      for (int k = 0; k < 4 && keep; ++k) {
        nz[k] = at(nu[k], nv[k]);
        if (nz[k] == 0) {
          if (options.normals) keep = false;  // needed for the normal
        } else if (jump_test && std::abs(nz[k] - z) > options.max_jump_rel * z) {
          keep = false;  // a depth edge: this pixel may be a mixed one
        }
      }
      if (!keep) continue;
      const Eigen::Vector3d p = unproject(K, u, v, z);
      if (options.normals) {
        const Eigen::Vector3d dx = unproject(K, nu[1], nv[1], nz[1]) - unproject(K, nu[0], nv[0], nz[0]);
        const Eigen::Vector3d dy = unproject(K, nu[3], nv[3], nz[3]) - unproject(K, nu[2], nv[2], nz[2]);
        Eigen::Vector3d normal = dx.cross(dy);
        const double len = normal.norm();
        if (!(len > 0) || !std::isfinite(len)) continue;
        normal /= len;
        if (normal.dot(p) > 0) normal = -normal;  // face the camera
        out.normals.push_back(normal);
      }
      out.points.push_back(p);
    }
  }
  return out;
}

bool project(const seq::Intrinsics& K, const Eigen::Vector3d& p_camera, double* u, double* v) {
  const double z = p_camera.z();
  if (!(z > 1e-12) || !p_camera.allFinite()) return false;
  if (u != nullptr) *u = K.fx * p_camera.x() / z + K.cx;
  if (v != nullptr) *v = K.fy * p_camera.y() / z + K.cy;
  return true;
}

}  // namespace efc::pipeline
