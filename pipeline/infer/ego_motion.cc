#include "pipeline/infer/ego_motion.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>

#include "pipeline/cloud/filters.h"
#include "pipeline/cloud/fusion.h"
#include "pipeline/cloud/icp.h"
#include "pipeline/cloud/kdtree.h"
#include "pipeline/infer/ego_anchor.h"

namespace efc::pipeline {

Eigen::Isometry3d mean_transform(const std::vector<Eigen::Isometry3d>& transforms, const std::vector<double>& weights) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  if (transforms.empty()) return out;
  const bool weighted = weights.size() == transforms.size();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  double total = 0;
  for (size_t i = 0; i < transforms.size(); ++i) {
    const Eigen::Isometry3d& T = transforms[i];
    const double w = weighted ? weights[i] : 1.0;
    t += w * T.translation();
    total += w;
    Eigen::Quaterniond q(T.linear());
    Eigen::Vector4d v(q.w(), q.x(), q.y(), q.z());
    Q += w * v * v.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(Q);
  Eigen::Vector4d v = eig.eigenvectors().col(3);
  out.linear() = Eigen::Quaterniond(v(0), v(1), v(2), v(3)).normalized().toRotationMatrix();
  out.translation() = t / (weighted ? total : static_cast<double>(transforms.size()));
  return out;
}

namespace {

// The parts the camera is registered on: the body (role object) and the
// parts that are still most of the time (effectors: most never move).
struct RegisteredParts {
  const std::vector<int>& body;
  const std::vector<int>& mostly_still;
};

// A mostly-still part counts for at most this share of a frame's points
// besides it: where the body and the room constrain the camera, one that
// moves (a lid opening) pulls it little; where they leave a direction
// nearly free, it is what holds the camera there.
constexpr double kMostlyStillShare = 0.3;

Cloud static_cloud(const Observations& obs, const std::vector<int>& parts, int frame) {
  Cloud c;
  for (int p : parts) c = concatenate(c, obs.parts[p].clouds[frame]);
  return c;
}

// What the camera is registered on: the static parts, the room around
// them (Observations::background) and the mostly-still parts, thinned to
// kMostlyStillShare of the rest together.
Cloud scene_cloud(const Observations& obs, const RegisteredParts& parts, int frame) {
  Cloud c = static_cloud(obs, parts.body, frame);
  if (frame < static_cast<int>(obs.background.size())) c = concatenate(c, obs.background[frame]);
  Cloud still = static_cloud(obs, parts.mostly_still, frame);
  if (still.size() > 0) {
    // At least one point: thin() leaves a cloud alone for a limit of 0.
    thin(&still, std::max(1, static_cast<int>(kMostlyStillShare * static_cast<double>(c.size()))));
    c = concatenate(c, still);
  }
  return c;
}

// Every registered frame's `cloud_of(f)` fused in the refined world frame.
template <typename CloudOf>
Cloud fuse_registered(const EgoMotion& ego, const CloudOf& cloud_of) {
  FusionOptions fo;
  fo.voxel = 0.006;
  fo.min_observations = 3;
  PartFusion fusion(fo);
  for (size_t f = 0; f < ego.correction.size(); ++f) {
    if (!ego.registered[f]) continue;
    Cloud c = cloud_of(static_cast<int>(f));
    transform_cloud(ego.correction[f], &c);
    fusion.add_frame(c);
  }
  return fusion.fused();
}

// Registers one frame onto `model` from `init`.
void register_one(const Observations& obs, const RegisteredParts& parts, const Cloud& model, const KdTree& tree,
                  const IcpOptions& icp, bool coarse_first, int f, const Eigen::Isometry3d& init, EgoMotion* out) {
  const Cloud c = scene_cloud(obs, parts, f);
  if (c.size() < 50) {
    out->registered[f] = false;
    out->correction[f] = init;
    return;
  }
  IcpResult r;
  r.transform = init;
  if (coarse_first) {
    // The drift can be a few centimetres.
    IcpOptions coarse = icp;
    coarse.max_correspondence = 0.08;
    coarse.kernel_scale = 0.02;
    coarse.max_iterations = 15;
    r = icp_point_to_plane(c, model, tree, init, coarse);
  }
  r = icp_point_to_plane(c, model, tree, r.transform, icp);
  out->registered[f] = r.inlier_fraction > 0.3 && r.correspondences >= 30;
  out->correction[f] = out->registered[f] ? r.transform : init;
  out->rmse[f] = r.rmse;
  out->inliers[f] = r.inlier_fraction;
}

// Pass 1: every frame onto the reference frame's points, from the tracker's
// own pose (no correction). Where the scene leaves a direction nearly free (a
// camera close to a fridge in front of a wall sees parallel planes: a slide
// along them is barely constrained) ICP leaves that direction where it
// started, and the tracker's pose is the best guess there: starting from the
// neighbour's correction instead carried each frame's error along that
// direction into the next, a random walk of its own (4 cm on one synthetic
// recording, where the tracker was off by 1.4 cm). A frame that does not
// register from its own pose is tried again from its registered neighbour's
// correction (a fast turn).
void register_from_tracker(const Observations& obs, const RegisteredParts& parts, const Cloud& model,
                           const IcpOptions& icp, int reference, EgoMotion* out) {
  const KdTree tree(model.points);
  const int n = static_cast<int>(obs.times.size());
  auto one = [&](int f, int neighbour) {
    register_one(obs, parts, model, tree, icp, true, f, Eigen::Isometry3d::Identity(), out);
    if (!out->registered[f] && neighbour >= 0 && neighbour < n && out->registered[neighbour])
      register_one(obs, parts, model, tree, icp, true, f, out->correction[neighbour], out);
  };
  one(reference, -1);
  for (int f = reference + 1; f < n; ++f) one(f, f - 1);
  for (int f = reference - 1; f >= 0; --f) one(f, f + 1);
}

// Pass 2: every frame onto the fused model from its pass-1 correction; the
// frames are independent now, so they run in parallel.
void register_refined(const Observations& obs, const RegisteredParts& parts, const Cloud& model,
                      const IcpOptions& icp, int threads, EgoMotion* out) {
  const KdTree tree(model.points);
  const int n = static_cast<int>(obs.times.size());
  const std::vector<Eigen::Isometry3d> start = out->correction;
  std::atomic<int> next{0};
  auto worker = [&]() {
    for (int f = next++; f < n; f = next++) register_one(obs, parts, model, tree, icp, false, f, start[f], out);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

}  // namespace

EgoMotion refine_ego_motion(const Observations& obs, const std::vector<int>& static_parts, int threads,
                            const ProgressFn& progress, const std::vector<int>& mostly_still_parts) {
  const RegisteredParts registered{static_parts, mostly_still_parts};
  const auto start = std::chrono::steady_clock::now();
  EgoMotion out;
  const int n = static_cast<int>(obs.times.size());
  out.correction.assign(n, Eigen::Isometry3d::Identity());
  out.registered.assign(n, false);
  out.rmse.assign(n, 0);
  out.inliers.assign(n, 0);
  if (n == 0 || static_parts.empty()) return out;

  // The reference: the frame that sees the most of the static parts.
  size_t best = 0;
  for (int f = 0; f < n; ++f) {
    size_t s = 0;
    for (int p : static_parts) s += obs.parts[p].clouds[f].size();
    if (s > best) best = s, out.reference_frame = f;
  }
  if (out.reference_frame < 0) return out;

  IcpOptions icp;
  icp.max_correspondence = 0.03;
  icp.kernel_scale = 0.006;
  icp.max_iterations = 20;
  icp.subsample = 1500;

  // Pass 1: onto the reference frame's points.
  Cloud model = scene_cloud(obs, registered, out.reference_frame);
  register_from_tracker(obs, registered, model, icp, out.reference_frame, &out);
  if (progress) progress("infer: camera poses registered (pass 1)");

  // Pass 2: onto every registered frame fused (a surface seen from all
  // sides, not one view's).
  Cloud fused = fuse_registered(out, [&](int f) { return scene_cloud(obs, registered, f); });
  if (fused.size() >= 200 && fused.has_normals()) {
    model = std::move(fused);
    register_refined(obs, registered, model, icp, threads, &out);
  }
  if (progress) progress("infer: camera poses registered (pass 2)");

  // Frames that could not be registered take their nearest registered
  // neighbour's correction.
  for (int f = 0; f < n; ++f) {
    if (out.registered[f]) continue;
    int best_f = -1;
    for (int d = 1; d < n && best_f < 0; ++d) {
      if (f - d >= 0 && out.registered[f - d]) best_f = f - d;
      else if (f + d < n && out.registered[f + d]) best_f = f + d;
    }
    if (best_f >= 0) out.correction[f] = out.correction[best_f];
  }

  // Anchor: drift is zero at the start, so the first frames place the
  // model in the world best; how much better than later ones, the
  // corrections' own noise says (ego_anchor.h).
  Cloud reference_points = static_cloud(obs, static_parts, out.reference_frame);
  transform_cloud(out.correction[out.reference_frame], &reference_points);
  const EgoAnchor anchor = anchor_refined_world(obs.times, out.correction, out.registered,
                                                reference_points.size() == 0 ? Eigen::Vector3d::Zero()
                                                                         : centroid(reference_points));
  for (Eigen::Isometry3d& T : out.correction) T = anchor.model_to_world * T;
  out.anchor = anchor;
  // The caller gets the object's static parts alone (the object frame is
  // fitted to them), not the room: fused, or where too little survives the
  // fusion (a short, small recording), the reference frame's own points.
  out.model = fuse_registered(out, [&](int f) { return static_cloud(obs, static_parts, f); });
  if (out.model.size() < 200 || !out.model.has_normals()) {
    out.model = static_cloud(obs, static_parts, out.reference_frame);
    transform_cloud(out.correction[out.reference_frame], &out.model);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace efc::pipeline
