#include "pipeline/infer/observations.h"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>

#include "pipeline/cloud/depth_points.h"
#include "pipeline/cloud/filters.h"
#include "pipeline/infer/motion_masks.h"

namespace efc::pipeline {

Eigen::Isometry3d pose_to_isometry(const seq::Pose& pose) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(pose.q[3], pose.q[0], pose.q[1], pose.q[2]).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(pose.p[0], pose.p[1], pose.p[2]);
  return T;
}

namespace {

// The pixels outside `mask` within `radius` of it (a square
// neighbourhood), looked for only about the mask's bounding box: per row,
// then per column of that, the distance to the nearest set pixel on
// either side, from one sweep each way.
seq::Image8 ring_outside(const seq::Image8& mask, int radius) {
  const int w = mask.width, h = mask.height;
  seq::Image8 out = mask;
  std::fill(out.pixels.begin(), out.pixels.end(), 0);
  int u0 = w, u1 = -1, v0 = h, v1 = -1;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      if (mask.pixels[static_cast<size_t>(v) * w + u]) {
        u0 = std::min(u0, u), u1 = std::max(u1, u);
        v0 = std::min(v0, v), v1 = std::max(v1, v);
      }
  if (u1 < 0) return out;
  u0 = std::max(0, u0 - radius), u1 = std::min(w - 1, u1 + radius);
  v0 = std::max(0, v0 - radius), v1 = std::min(h - 1, v1 + radius);
  const int bw = u1 - u0 + 1, bh = v1 - v0 + 1;
  auto near_one = [radius](const auto& at, int n, std::vector<uint8_t>* near) {
    near->assign(n, 0);
    int last = -radius - 1;
    for (int i = 0; i < n; ++i) {
      if (at(i)) last = i;
      (*near)[i] = i - last <= radius;
    }
    last = n + radius;
    for (int i = n - 1; i >= 0; --i) {
      if (at(i)) last = i;
      (*near)[i] |= last - i <= radius;
    }
  };
  std::vector<uint8_t> rows(static_cast<size_t>(bw) * bh), line;
  for (int v = 0; v < bh; ++v) {
    near_one([&](int u) { return mask.pixels[static_cast<size_t>(v + v0) * w + u + u0] != 0; }, bw, &line);
    std::copy(line.begin(), line.end(), rows.begin() + static_cast<long>(v) * bw);
  }
  for (int u = 0; u < bw; ++u) {
    near_one([&](int v) { return rows[static_cast<size_t>(v) * bw + u] != 0; }, bh, &line);
    for (int v = 0; v < bh; ++v) {
      const size_t i = static_cast<size_t>(v + v0) * w + u + u0;
      out.pixels[i] = line[v] && !mask.pixels[i] ? 255 : 0;
    }
  }
  return out;
}

}  // namespace

bool observe(const seq::Sequence& sequence, const ObserveOptions& options, Diagnostics& diags,
             const ProgressFn& progress, Observations* out) {
  const seq::Meta& meta = sequence.meta();
  const std::string meta_file = sequence.dir() + "/meta.json";
  bool ok = true;
  if (!sequence.has_depth()) {
    diags.error("E1050", sequence.dir(), 0, 0, "",
                "efc infer needs depth: the sequence has no depth/ folder",
                "put an external depth model's maps in " + sequence.dir() +
                    "/depth/ (16-bit PNG, metres = value x depth_scale, one per frame)");
    ok = false;
  }
  if (!sequence.has_poses()) {
    diags.error("E1051", sequence.dir(), 0, 0, "",
                "efc infer needs camera poses: the sequence has no poses.txt",
                "write the camera-to-world pose of every frame (TUM lines) to " + sequence.dir() +
                    "/poses.txt, e.g. from a SLAM or visual odometry run");
    ok = false;
  }
  if (!ok) return false;

  std::vector<seq::Pose> poses;
  if (!sequence.read_poses(diags, &poses)) return false;
  if (sequence.has_hands() && !sequence.read_hands(diags, &out->hands)) return false;
  out->times.clear();
  out->camera_to_world.clear();
  for (const seq::Pose& p : poses) {
    out->times.push_back(p.t);
    out->camera_to_world.push_back(pose_to_isometry(p));
  }

  // Which parts, from which mask folders: meta.json's parts (the hand left
  // out); without "parts", the role masks.
  out->parts.clear();
  out->background.clear();
  const std::vector<std::string>& folders = sequence.mask_names();
  auto has_folder = [&](const std::string& n) { return std::binary_search(folders.begin(), folders.end(), n); };
  std::vector<std::pair<std::string, std::string>> parts = meta.parts;
  if (parts.empty()) {
    for (const char* role : {"object", "receptor", "effector"})
      if (has_folder(role)) parts.push_back({role, role});
  }
  for (const auto& [name, role] : parts) {
    if (role == "hand" || name == "hand") continue;
    if (!has_folder(name)) {
      diags.warning("E1052", meta_file, 0, 0, "/parts/" + name,
                    "part '" + name + "' has no masks (masks/" + name + "/): it is left out of the object",
                    "supply an external segmenter's masks in masks/" + name + "/");
      continue;
    }
    PartFrames pf;
    pf.name = name;
    pf.role = role;
    pf.mask = name;
    pf.clouds.resize(meta.frames);
    pf.outlines.resize(meta.frames);
    pf.pixels.assign(meta.frames, 0);
    out->parts.push_back(std::move(pf));
  }
  if (out->parts.empty()) {
    diags.warning("E1053", sequence.dir(), 0, 0, "",
                  "no part masks (masks/<part>/): falling back to what moves in the depth once the camera's own "
                  "motion is taken out; parts cannot be named or told from the hand this way",
                  "supply an external segmenter's masks in masks/<part>/, one folder per part listed in meta.json");
    if (!observe_by_motion(sequence, options, diags, progress, out)) return false;
    bool moved = false;
    for (const Cloud& c : out->parts.empty() ? std::vector<Cloud>{} : out->parts.back().clouds) moved |= c.size() > 0;
    if (!moved) {
      diags.error("E1053", sequence.dir(), 0, 0, "",
                  "no part masks, and nothing in the depth moves: there is no part to find",
                  "supply an external segmenter's masks in masks/<part>/");
      return false;
    }
    return true;
  }

  // The hand's mask, when there is one, only keeps the hand out of the
  // background.
  std::string hand_mask;
  for (const auto& [name, role] : meta.parts)
    if ((role == "hand" || name == "hand") && has_folder(name)) hand_mask = name;
  if (hand_mask.empty() && has_folder("hand")) hand_mask = "hand";
  out->background.assign(meta.frames, Cloud{});
  out->hand_clouds.clear();
  if (!hand_mask.empty() && !out->hands.empty()) out->hand_clouds.assign(meta.frames, Cloud{});

  // Frames in parallel: each worker takes the next frame; PNG decoding is
  // most of the time here.
  std::atomic<int> next{0}, done{0};
  std::mutex diag_mutex;
  std::atomic<bool> failed{false};
  BackprojectOptions bp;
  bp.stride = std::max(1, options.stride);
  auto worker = [&]() {
    Diagnostics local;
    for (int f = next++; f < meta.frames && !failed; f = next++) {
      seq::Image16 depth;
      if (!sequence.read_depth(f, local, &depth)) {
        failed = true;
        break;
      }
      // Pixels some mask claims: not background.
      seq::Image8 claimed;
      if (options.background) {
        claimed.width = depth.width, claimed.height = depth.height, claimed.channels = 1;
        claimed.pixels.assign(static_cast<size_t>(depth.width) * depth.height, 0);
      }
      auto claim = [&](const seq::Image8& mask) {
        if (!options.background || mask.pixels.size() != claimed.pixels.size()) return;
        for (size_t i = 0; i < mask.pixels.size(); ++i) claimed.pixels[i] |= mask.pixels[i] != 0;
      };
      for (PartFrames& pf : out->parts) {
        seq::Image8 mask;
        if (!sequence.read_mask(pf.mask, f, local, &mask)) {
          failed = true;
          break;
        }
        claim(mask);
        int count = 0;
        for (uint8_t v : mask.pixels) count += v != 0;
        pf.pixels[f] = count;
        if (count == 0) continue;
        // Small moving parts need every pixel they have; the body has plenty.
        BackprojectOptions part_bp = bp;
        if (pf.role != "object") part_bp.stride = 1;
        Cloud c = backproject(depth, meta.depth_scale, meta.intrinsics, &mask, part_bp);
        // The outline's points by the same test and thinned by the same
        // share: a voxel's count inside and outside compare like for like.
        const seq::Image8 ring = ring_outside(mask, kOutlinePixels);
        Cloud outline = backproject(depth, meta.depth_scale, meta.intrinsics, &ring, part_bp);
        const size_t seen = c.size();
        thin(&c, pf.role == "object" ? options.max_points_static : options.max_points_moving);
        if (seen > 0 && c.size() < seen)
          thin(&outline, std::max(1, static_cast<int>(static_cast<double>(outline.size()) * c.size() / seen)));
        transform_cloud(out->camera_to_world[f], &c);
        transform_cloud(out->camera_to_world[f], &outline);
        pf.clouds[f] = std::move(c);
        pf.outlines[f] = std::move(outline);
      }
      if (failed) break;
      if (!hand_mask.empty() && (options.background || !out->hand_clouds.empty())) {
        seq::Image8 mask;
        if (!sequence.read_mask(hand_mask, f, local, &mask)) {
          failed = true;
          break;
        }
        claim(mask);
        // The hand's own points near its contact point, every pixel (a
        // fingertip on a button is a few dozen of them), for the grip.
        if (!out->hand_clouds.empty() && f < static_cast<int>(out->hands.size()) && out->hands[f].seen) {
          BackprojectOptions hand_bp = bp;
          hand_bp.stride = 1;
          Cloud all = backproject(depth, meta.depth_scale, meta.intrinsics, &mask, hand_bp);
          transform_cloud(out->camera_to_world[f], &all);
          const Eigen::Vector3d at(out->hands[f].p[0], out->hands[f].p[1], out->hands[f].p[2]);
          Cloud& near = out->hand_clouds[f];
          for (size_t i = 0; i < all.size(); ++i) {
            if ((all.points[i] - at).norm() >= kHandCloudRadius) continue;
            near.points.push_back(all.points[i]);
            if (all.has_normals()) near.normals.push_back(all.normals[i]);
          }
          thin(&near, options.max_points_moving);
        }
      }
      if (options.background) {
        for (uint8_t& v : claimed.pixels) v = v ? 0 : 255;  // now: the unclaimed pixels
        BackprojectOptions room = bp;
        room.stride = std::max(1, options.background_stride);
        room.max_depth = options.background_max_depth;
        Cloud c = backproject(depth, meta.depth_scale, meta.intrinsics, &claimed, room);
        thin(&c, options.max_points_background);
        transform_cloud(out->camera_to_world[f], &c);
        out->background[f] = std::move(c);
      }
      const int d = ++done;
      if (progress && (d % 50 == 0 || d == meta.frames))
        progress("infer: read " + std::to_string(d) + "/" + std::to_string(meta.frames) + " frames");
    }
    std::lock_guard<std::mutex> lock(diag_mutex);
    for (const Diagnostic& d : local.items()) diags.add(d);
  };
  const int threads = std::max(1, std::min(options.threads, meta.frames));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  return !failed;
}

}  // namespace efc::pipeline
