#include "pipeline/infer/part_tracking.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "pipeline/cloud/fusion.h"
#include "pipeline/cloud/icp.h"
#include "pipeline/cloud/kdtree.h"

namespace efc::pipeline {

Cloud part_cloud_in_object(const Observations& obs, int part, int frame,
                           const std::vector<Eigen::Isometry3d>& to_object) {
  Cloud c = obs.parts[part].clouds[frame];
  transform_cloud(to_object[frame], &c);
  return c;
}

namespace {

constexpr size_t kMinPoints = 12;

// Re-acquisition: a part that moves by tens of degrees between two frames
// (a door flung open, a lid a servo snaps up) leaves ICP's basin, and every
// later frame of that state is lost with it. A frame that no start
// registers is searched for globally: its points' centroid onto the
// model's, turned about the model's principal axes and the frame's axes by
// every kReacquireStep up to half a turn, plus every distinct pose already
// registered (a state seen once seeds its recurrences). Only frames with
// enough points to tell a pose, and at most kMaxReacquisitions per pass.
constexpr size_t kReacquireMinPoints = 60;
constexpr int kMaxReacquisitions = 40;
constexpr double kReacquireStep = 30.0 * 3.14159265358979323846 / 180.0;

Eigen::Matrix3d principal_axes(const Cloud& c) {
  const Eigen::Vector3d mean = centroid(c);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : c.points) cov += (p - mean) * (p - mean).transpose();
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors();
}

// Starts (frame -> model) for a frame that chained starts did not register.
std::vector<Eigen::Isometry3d> reacquisition_starts(const Cloud& frame, const Cloud& model,
                                                    const Eigen::Matrix3d& model_axes,
                                                    const std::vector<Eigen::Isometry3d>& seen) {
  std::vector<Eigen::Isometry3d> starts = seen;
  const Eigen::Vector3d cf = centroid(frame), cm = centroid(model);
  std::vector<Eigen::Vector3d> axes = {model_axes.col(0), model_axes.col(1), model_axes.col(2),
                                       Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                       Eigen::Vector3d::UnitZ()};
  auto add = [&](const Eigen::Matrix3d& R) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R;
    T.translation() = cm - R * cf;
    starts.push_back(T);
  };
  add(Eigen::Matrix3d::Identity());
  for (const Eigen::Vector3d& a : axes)
    for (double angle = kReacquireStep; angle <= 3.14159265358979323846 + 1e-9; angle += kReacquireStep) {
      add(Eigen::AngleAxisd(angle, a.normalized()).toRotationMatrix());
      if (angle < 3.14159265358979323846 - 1e-9) add(Eigen::AngleAxisd(-angle, a.normalized()).toRotationMatrix());
    }
  return starts;
}

// A thin flat part (a lid, a door panel) shows one face at rest and often
// the other once it opens (a chest lid lifts its inside towards the person
// in front). A model of the seen face alone then fits the open part only
// flipped over. The tracking model gets the unseen face too: the seen face's
// points moved kBackFaceDepth behind it, facing the other way (the true
// thickness is unknown; a centimetre or two for the parts in question).
constexpr double kBackFaceDepth = 0.015;

Cloud with_back_face(const Cloud& model) {
  if (!model.has_normals() || model.size() < 50) return model;
  const Eigen::Vector3d mean = centroid(model);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : model.points) cov += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov / static_cast<double>(model.size()));
  const double thin = std::sqrt(std::max(0.0, eig.eigenvalues()(0))), narrow = std::sqrt(eig.eigenvalues()(1));
  if (!(narrow > 0.02 && thin < 0.15 * narrow)) return model;  // not a plate of a few cm
  Eigen::Vector3d n = eig.eigenvectors().col(0);
  Eigen::Vector3d mean_normal = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& m : model.normals) mean_normal += m;
  if (n.dot(mean_normal) < 0) n = -n;
  size_t on_face = 0;
  for (const Eigen::Vector3d& m : model.normals) on_face += m.dot(n) >= 0.7;
  if (on_face * 2 < model.size()) return model;  // mostly edges or a curved part
  Cloud out = model;
  for (size_t i = 0; i < model.size(); ++i) {
    if (model.normals[i].dot(n) < 0.7) continue;  // edges keep one side
    out.points.push_back(model.points[i] - kBackFaceDepth * n);
    out.normals.push_back(-model.normals[i]);
  }
  return out;
}

// The mean distance between the model's points moved by a and by b (at most
// 200 points).
double mean_displacement(const Cloud& model, const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const size_t stride = std::max<size_t>(1, model.size() / 200);
  double sum = 0;
  int count = 0;
  for (size_t i = 0; i < model.size(); i += stride, ++count) sum += (a * model.points[i] - b * model.points[i]).norm();
  return count ? sum / count : 0.0;
}

// Whether pose a is within 10 degrees and 2 cm of one of `poses`.
bool near_any(const Eigen::Isometry3d& a, const std::vector<Eigen::Isometry3d>& poses) {
  for (const Eigen::Isometry3d& b : poses) {
    const Eigen::Isometry3d d = a * b.inverse();
    if (Eigen::AngleAxisd(d.rotation()).angle() < 0.17 && d.translation().norm() < 0.02) return true;
  }
  return false;
}

// ICP maps frame points onto the model: the inverse of the part's motion.
// `seeded`: pass 2. A frame registered in pass 1 starts from its pass-1
// motion, fine alignment only; the others are tracked as in pass 1.
void register_frames(const Observations& obs, int part, const std::vector<Eigen::Isometry3d>& to_object,
                     const Cloud& model, bool seeded, PartTrack* out) {
  const std::vector<bool> seed_ok = out->tracked;
  std::vector<Eigen::Isometry3d> seed(out->motion.size());
  for (size_t f = 0; f < seed.size(); ++f) seed[f] = out->motion[f].inverse();
  const KdTree tree(model.points);
  const int n = static_cast<int>(obs.times.size());
  IcpOptions fine;
  fine.max_correspondence = 0.015;
  fine.kernel_scale = 0.004;
  fine.max_iterations = 25;
  fine.subsample = 600;
  fine.degenerate_threshold = 0.05;  // noise along a near-symmetry is not motion
  fine.min_normal_dot = 0.5;         // no flipped matches
  IcpOptions coarse = fine;
  coarse.max_correspondence = 0.05;
  coarse.kernel_scale = 0.015;
  coarse.max_iterations = 12;
  // to_model[f]: the ICP result (frame -> model). A frame that fails keeps
  // its start, but only registered frames seed the next ones (extrapolating
  // from guesses would run away).
  std::vector<Eigen::Isometry3d> to_model(n, Eigen::Isometry3d::Identity());
  int last_good = -1, before_last_good = -1;
  const Eigen::Matrix3d model_axes = principal_axes(model);
  IcpOptions search = coarse;
  search.subsample = 250;
  search.max_iterations = 20;
  std::vector<Eigen::Isometry3d> distinct;  // registered poses, 10 degrees / 2 cm apart
  int reacquisitions = 0;
  auto one = [&](int f) {
    std::vector<Eigen::Isometry3d> starts;
    const bool from_seed = seeded && seed_ok[f];
    if (from_seed) {
      starts.push_back(seed[f]);
    } else if (last_good >= 0) {
      // The last registered pose first, then constant velocity (the last
      // registered step again). Velocity first would carry any step along a
      // direction the shape cannot show (a lid sliding on its own plane,
      // which ICP leaves at its start) into every later frame: a steady
      // drift that looks like a slide.
      starts.push_back(to_model[last_good]);
      if (before_last_good >= 0 && std::abs(last_good - before_last_good) == 1)
        starts.push_back(to_model[last_good] * (to_model[before_last_good].inverse() * to_model[last_good]));
    }
    if (!from_seed) starts.push_back(Eigen::Isometry3d::Identity());  // the reference configuration
    const Cloud c = part_cloud_in_object(obs, part, f, to_object);
    out->tracked[f] = false;
    to_model[f] = starts.front();
    if (c.size() < kMinPoints) return;
    IcpResult best;
    bool have = false;
    for (const Eigen::Isometry3d& start : starts) {
      IcpResult r;
      r.transform = start;
      if (!from_seed) r = icp_point_to_plane(c, model, tree, start, coarse);
      r = icp_point_to_plane(c, model, tree, r.transform, fine);
      if (!have || r.inlier_fraction > best.inlier_fraction + 1e-9) best = r, have = true;
      if (best.inlier_fraction > 0.6) break;  // good enough: skip the other starts
    }
    if (!from_seed && best.inlier_fraction <= 0.5 && c.size() >= kReacquireMinPoints &&
        reacquisitions < kMaxReacquisitions) {
      ++reacquisitions;
      // A flat part fits itself in many poses (a lid spun half a turn on
      // its own plane, or slid along it, is the same plane): among the poses
      // that fit about as well as the best, those within 10 degrees of the
      // smallest turn from the last registered pose, and of those the
      // smallest motion (the mean displacement of the model's points).
      // Where a plate's outline is out of view its place on its plane stays
      // uncertain.
      std::vector<IcpResult> results;
      double most = 0;
      for (const Eigen::Isometry3d& start : reacquisition_starts(c, model, model_axes, distinct)) {
        results.push_back(icp_point_to_plane(c, model, tree, start, search));
        most = std::max(most, results.back().inlier_fraction);
      }
      const Eigen::Isometry3d before = last_good >= 0 ? to_model[last_good] : Eigen::Isometry3d::Identity();
      auto turn_of = [&](const IcpResult& r) {
        return Eigen::AngleAxisd((r.transform * before.inverse()).rotation()).angle();
      };
      double least_turn = 1e9;
      for (const IcpResult& r : results)
        if (r.inlier_fraction >= most - 0.1) least_turn = std::min(least_turn, turn_of(r));
      IcpResult found;
      double nearest = 1e9;
      for (const IcpResult& r : results) {
        if (r.inlier_fraction < most - 0.1 || turn_of(r) > least_turn + 0.17) continue;
        const double moved = mean_displacement(model, before.inverse(), r.transform.inverse());
        if (moved < nearest) nearest = moved, found = r;
      }
      if (found.inlier_fraction > 0.3) {
        IcpResult r = icp_point_to_plane(c, model, tree, found.transform, coarse);
        r = icp_point_to_plane(c, model, tree, r.transform, fine);
        if (r.inlier_fraction > best.inlier_fraction) best = r;
      }
    }
    const IcpResult& r = best;
    const bool good = r.inlier_fraction > 0.5 && r.correspondences >= kMinPoints;
    out->tracked[f] = good;
    out->rmse[f] = r.rmse;
    out->inliers[f] = r.inlier_fraction;
    out->conditioning[f] = r.normalized_eigenvalues(0);
    if (good) {
      to_model[f] = r.transform;
      if (!near_any(r.transform, distinct)) distinct.push_back(r.transform);
      before_last_good = last_good;
      last_good = f;
    }
  };
  const int ref = out->reference_frame;
  one(ref);
  const int ref_good = last_good;
  for (int f = ref + 1; f < n; ++f) one(f);
  last_good = ref_good, before_last_good = -1;
  for (int f = ref - 1; f >= 0; --f) one(f);
  out->frames_tracked = 0;
  for (int f = 0; f < n; ++f) {
    out->motion[f] = to_model[f].inverse();
    out->frames_tracked += out->tracked[f];
  }
}

// The frame to model the part on: the one that sees most of it, among the
// frames where it is where it usually is. Segmenters swap identities now and
// then, and a frame whose "knob" mask holds the door would make the door the
// model; its centroid gives it away.
int reference_frame(const Observations& obs, int part, const std::vector<Eigen::Isometry3d>& to_object) {
  const PartFrames& pf = obs.parts[part];
  const int n = static_cast<int>(pf.clouds.size());
  std::vector<Eigen::Vector3d> centre(n, Eigen::Vector3d::Zero());
  std::vector<double> xs, ys, zs, counts;
  for (int f = 0; f < n; ++f) {
    const Cloud& c = pf.clouds[f];
    if (c.size() < kMinPoints) continue;
    for (const Eigen::Vector3d& p : c.points) centre[f] += p;
    centre[f] = to_object[f] * Eigen::Vector3d(centre[f] / static_cast<double>(c.size()));
    xs.push_back(centre[f].x()), ys.push_back(centre[f].y()), zs.push_back(centre[f].z());
    counts.push_back(static_cast<double>(c.size()));
  }
  if (xs.empty()) return -1;
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  const Eigen::Vector3d typical(median(xs), median(ys), median(zs));
  std::vector<double> spread;
  for (int f = 0; f < n; ++f)
    if (pf.clouds[f].size() >= kMinPoints) spread.push_back((centre[f] - typical).norm());
  // A part that moves spreads its centroids; twice the median distance
  // keeps its usual places and drops the strays.
  const double keep = std::max(0.02, 2.0 * median(spread));
  const double most = 2.0 * median(counts);
  int best = -1;
  size_t best_count = 0;
  for (int f = 0; f < n; ++f) {
    const size_t count = pf.clouds[f].size();
    if (count < kMinPoints || (centre[f] - typical).norm() > keep || count > most) continue;
    if (count > best_count) best_count = count, best = f;
  }
  return best;
}

}  // namespace

PartTrack track_part(const Observations& obs, int part, const std::vector<Eigen::Isometry3d>& to_object) {
  const auto start = std::chrono::steady_clock::now();
  PartTrack out;
  out.part = part;
  const int n = static_cast<int>(obs.times.size());
  out.motion.assign(n, Eigen::Isometry3d::Identity());
  out.tracked.assign(n, false);
  out.rmse.assign(n, 0);
  out.inliers.assign(n, 0);
  out.conditioning.assign(n, 0);
  out.reference_frame = reference_frame(obs, part, to_object);
  if (out.reference_frame < 0) return out;

  // Pass 1: onto the reference frame's own points.
  Cloud model = part_cloud_in_object(obs, part, out.reference_frame, to_object);
  register_frames(obs, part, to_object, with_back_face(model), false, &out);
  // Pass 2: onto every tracked frame fused in the reference configuration.
  // The model's resolution follows the part's size: 3 mm for a knob, up to
  // 1 cm for a door (a finer model of a large part only slows ICP).
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : model.points) box.extend(p);
  FusionOptions fo;
  fo.voxel = std::clamp(box.diagonal().norm() / 100.0, 0.003, 0.01);
  fo.min_observations = 2;
  PartFusion fusion(fo);
  for (int f = 0; f < n; ++f) {
    if (!out.tracked[f]) continue;
    Cloud c = part_cloud_in_object(obs, part, f, to_object);
    transform_cloud(out.motion[f].inverse(), &c);
    fusion.add_frame(c);
  }
  Cloud fused = fusion.fused();
  if (fused.size() >= model.size() && fused.has_normals()) {
    model = std::move(fused);
    register_frames(obs, part, to_object, with_back_face(model), true, &out);
  }
  out.model = std::move(model);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace efc::pipeline
