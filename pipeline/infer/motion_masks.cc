#include "pipeline/infer/motion_masks.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>

#include "pipeline/cloud/depth_points.h"

namespace efc::pipeline {

namespace {

constexpr int kOffset = 5;  // frames between the compared views

// Whether camera-frame point p (of frame i, already moved into frame k's
// camera) lies clearly in front of frame k's surface on the same ray.
bool in_front(const seq::Image16& depth_k, double scale, const seq::Intrinsics& K, const Eigen::Vector3d& p) {
  double u, v;
  if (!project(K, p, &u, &v)) return false;
  const int x = static_cast<int>(std::lround(u)), y = static_cast<int>(std::lround(v));
  if (x < 0 || y < 0 || x >= depth_k.width || y >= depth_k.height) return false;
  const uint16_t raw = depth_k.pixels[static_cast<size_t>(y) * depth_k.width + x];
  if (raw == 0) return false;
  const double z = raw * scale;
  const double tolerance = std::max(0.02, 0.03 * z);  // depth noise grows with range
  return p.z() < z - tolerance;
}

}  // namespace

bool observe_by_motion(const seq::Sequence& sequence, const ObserveOptions& options, Diagnostics& diags,
                       const ProgressFn& progress, Observations* out) {
  const seq::Meta& meta = sequence.meta();
  const int n = meta.frames;
  PartFrames body, moving;
  body.name = "body", body.role = "object", body.mask = "(motion)";
  moving.name = "moving", moving.role = "receptor", moving.mask = "(motion)";
  body.clouds.resize(n), moving.clouds.resize(n);
  body.pixels.assign(n, 0), moving.pixels.assign(n, 0);
  BackprojectOptions bp;
  bp.stride = std::max(2, options.stride);
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::mutex diag_mutex;
  auto worker = [&]() {
    Diagnostics local;
    for (int f = next++; f < n && !failed; f = next++) {
      seq::Image16 depth;
      if (!sequence.read_depth(f, local, &depth)) {
        failed = true;
        break;
      }
      const Cloud c = backproject(depth, meta.depth_scale, meta.intrinsics, nullptr, bp);
      std::vector<char> flag(c.size(), 0);
      for (int k : {f - kOffset, f + kOffset}) {
        if (k < 0 || k >= n) continue;
        seq::Image16 other;
        if (!sequence.read_depth(k, local, &other)) {
          failed = true;
          break;
        }
        const Eigen::Isometry3d i_to_k = out->camera_to_world[k].inverse() * out->camera_to_world[f];
        for (size_t p = 0; p < c.size(); ++p)
          if (!flag[p] && in_front(other, meta.depth_scale, meta.intrinsics, i_to_k * c.points[p])) flag[p] = 1;
      }
      Cloud still, moved;
      for (size_t p = 0; p < c.size(); ++p) {
        Cloud& dst = flag[p] ? moved : still;
        dst.points.push_back(out->camera_to_world[f] * c.points[p]);
        if (c.has_normals()) dst.normals.push_back(out->camera_to_world[f].linear() * c.normals[p]);
      }
      body.clouds[f] = std::move(still);
      moving.clouds[f] = std::move(moved);
    }
    std::lock_guard<std::mutex> lock(diag_mutex);
    for (const Diagnostic& d : local.items()) diags.add(d);
  };
  const int threads = std::max(1, std::min(options.threads, n));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (failed) return false;
  if (progress) progress("infer: motion masks computed for " + std::to_string(n) + " frames");

  // The region where things moved: around the median moving point.
  std::vector<double> xs, ys, zs;
  for (const Cloud& c : moving.clouds)
    for (const Eigen::Vector3d& p : c.points) xs.push_back(p.x()), ys.push_back(p.y()), zs.push_back(p.z());
  if (xs.empty()) return true;  // nothing moved: observe() reports it
  auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  const Eigen::Vector3d centre(median(xs), median(ys), median(zs));
  auto keep_near = [&](PartFrames* pf, int max_points) {
    for (int f = 0; f < n; ++f) {
      Cloud& c = pf->clouds[f];
      Cloud kept;
      const size_t total = c.size();
      size_t inside = 0;
      for (size_t p = 0; p < total; ++p) inside += (c.points[p] - centre).norm() < kRegionRadius;
      const size_t step = std::max<size_t>(1, inside / std::max(1, max_points));
      size_t seen = 0;
      for (size_t p = 0; p < total; ++p) {
        if ((c.points[p] - centre).norm() >= kRegionRadius) continue;
        if (seen++ % step) continue;
        kept.points.push_back(c.points[p]);
        if (c.has_normals()) kept.normals.push_back(c.normals[p]);
      }
      pf->pixels[f] = static_cast<int>(inside);
      c = std::move(kept);
    }
  };
  keep_near(&body, options.max_points_static);
  keep_near(&moving, options.max_points_moving);
  out->parts.push_back(std::move(body));
  out->parts.push_back(std::move(moving));
  out->motion_masks = true;
  return true;
}

}  // namespace efc::pipeline
