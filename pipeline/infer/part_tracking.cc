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
#include "pipeline/infer/reacquisition.h"

namespace efc::pipeline {

namespace {

Cloud in_object(const std::vector<Cloud>& clouds, int frame, const std::vector<Eigen::Isometry3d>& to_object) {
  Cloud c = clouds[frame];
  transform_cloud(to_object[frame], &c);
  return c;
}

constexpr size_t kMinPoints = 12;

// A registration the track takes: most of the frame's points matched.
bool registered_well(const IcpResult& r) { return r.inlier_fraction > 0.5 && r.correspondences >= kMinPoints; }

// The part of a registration step `step` (model frame, applied on the left)
// that the registration of its last frame could see: its twist about that
// registration's Hessian centre, in the Hessian's normalised coordinates
// (IcpResult), keeps only the components along directions constrained
// above `threshold` (TrackOptions::carry_unseen_motion).
Eigen::Isometry3d seen_part_of_step(const Eigen::Isometry3d& step, const Eigen::Matrix<double, 6, 6>& hessian,
                                    const Eigen::Vector3d& centre, double scale, double threshold) {
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  const double weight_sum = hessian.block<3, 3>(3, 3).trace();
  if (!(scale > 0) || !(weight_sum > 0)) return Eigen::Isometry3d::Identity();
  const Eigen::AngleAxisd aa(step.linear());
  Vec6 y;
  y.head<3>() = scale * aa.angle() * aa.axis();
  y.tail<3>() = step * centre - centre;
  Vec6 d;
  d << 1 / scale, 1 / scale, 1 / scale, 1, 1, 1;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(d.asDiagonal() * hessian * d.asDiagonal() /
                                                                        weight_sum);
  Vec6 kept = Vec6::Zero();
  for (int k = 0; k < 6; ++k)
    if (eig.eigenvalues()(k) >= threshold) kept += eig.eigenvectors().col(k).dot(y) * eig.eigenvectors().col(k);
  const Eigen::Vector3d w = kept.head<3>() / scale;
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  if (w.norm() > 0) out.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
  out.translation() = centre + kept.tail<3>() - out.linear() * centre;
  return out;
}

// ICP maps frame points onto the model: the inverse of the part's motion.
// `seeded`: pass 2. A frame registered in pass 1 starts from its pass-1
// motion, fine alignment only; the others are tracked as in pass 1.
void register_frames(const std::vector<Cloud>& clouds, const std::vector<Eigen::Isometry3d>& to_object,
                     const Cloud& model, bool seeded, const TrackOptions& options, PartTrack* out) {
  const std::vector<bool> seed_ok = out->tracked;
  std::vector<Eigen::Isometry3d> seed(out->motion.size());
  for (size_t f = 0; f < seed.size(); ++f) seed[f] = out->motion[f].inverse();
  const KdTree tree(model.points);
  const int n = static_cast<int>(clouds.size());
  IcpOptions fine;
  fine.max_correspondence = 0.015;
  fine.kernel_scale = 0.004;
  fine.max_iterations = 25;
  fine.subsample = 600;
  fine.degenerate_threshold = kTrackDegenerateThreshold;
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
  // Frame f's registration, as the track reports it.
  auto record = [&](int f, const IcpResult& r, bool good) {
    out->tracked[f] = good;
    out->rmse[f] = r.rmse;
    out->inliers[f] = r.inlier_fraction;
    out->conditioning[f] = r.normalized_eigenvalues(0);
    out->hessian[f] = r.hessian;
    out->hessian_center[f] = r.hessian_center;
    out->hessian_scale[f] = r.scale_length;
    if (good) to_model[f] = r.transform;
  };
  // `m`, `m_tree`: the model registered onto (a run found again uses the
  // model with a plate's unseen face).
  auto one_onto = [&](int f, const Cloud& m, const KdTree& m_tree) {
    std::vector<Eigen::Isometry3d> starts;
    const bool from_seed = seeded && seed_ok[f];
    if (from_seed) {
      starts.push_back(seed[f]);
    } else if (last_good >= 0) {
      starts.push_back(to_model[last_good]);
      // Constant velocity: the last registered step again, per frame.
      if (before_last_good >= 0 && std::abs(last_good - before_last_good) == 1) {
        Eigen::Isometry3d step = to_model[last_good] * to_model[before_last_good].inverse();
        if (!options.carry_unseen_motion)
          step = seen_part_of_step(step, out->hessian[last_good], out->hessian_center[last_good],
                                   out->hessian_scale[last_good], kTrackDegenerateThreshold);
        starts.insert(starts.begin(), step * to_model[last_good]);
      }
    }
    // The reference configuration (TrackOptions::restart_from_reference).
    if (!from_seed && (options.restart_from_reference || last_good < 0 || std::abs(f - last_good) > kRegraspFrames))
      starts.push_back(Eigen::Isometry3d::Identity());
    const Cloud c = in_object(clouds, f, to_object);
    out->tracked[f] = false;
    to_model[f] = starts.front();
    if (c.size() < kMinPoints) return;
    IcpResult best;
    bool have = false;
    for (const Eigen::Isometry3d& start : starts) {
      IcpResult r;
      r.transform = start;
      if (!from_seed) r = icp_point_to_plane(c, m, m_tree, start, coarse);
      r = icp_point_to_plane(c, m, m_tree, r.transform, fine);
      if (!have || r.inlier_fraction > best.inlier_fraction + 1e-9) best = r, have = true;
      if (best.inlier_fraction > 0.6) break;  // good enough: skip the other starts
    }
    const bool good = registered_well(best);
    record(f, best, good);
    if (good) {
      before_last_good = last_good;
      last_good = f;
    }
  };
  auto one = [&](int f) { one_onto(f, model, tree); };
  const int ref = out->reference_frame;
  one(ref);
  const int ref_good = last_good;
  for (int f = ref + 1; f < n; ++f) one(f);
  last_good = ref_good, before_last_good = -1;
  for (int f = ref - 1; f >= 0; --f) one(f);
  if (!seeded && options.reacquire_leaps) {
    // Held states the chain lost (reacquisition.h): the run's frame with
    // most points from the global starts, then the chain through the run,
    // both onto the model with a plate's unseen face.
    IcpOptions search = coarse;
    search.subsample = 250;
    search.max_iterations = 20;
    const Cloud both_faces = with_back_face(model);
    const KdTree both_tree(both_faces.points);
    // How far the part's points jump from frame a to frame b (0 where
    // either is unseen): only a leap beyond the registration's reach (the
    // coarse correspondence distance) at an end of the run is searched for.
    auto jump = [&](int a, int b) {
      if (a < 0 || b >= n || clouds[a].size() < kMinPoints || clouds[b].size() < kMinPoints) return 0.0;
      return (to_object[a] * centroid(clouds[a]) - to_object[b] * centroid(clouds[b])).norm();
    };
    for (int begin = 0; begin < n;) {
      int end = begin;
      while (end < n && !out->tracked[end] && out->inliers[end] < kReacquireLost &&
             clouds[end].size() >= kReacquireMinPoints)
        ++end;
      if (end - begin < kReacquireRun ||
          std::max(jump(begin - 1, begin), jump(end - 1, end)) < coarse.max_correspondence) {
        begin = end + 1;
        continue;
      }
      int anchor = begin;
      for (int f = begin; f < end; ++f)
        if (clouds[f].size() > clouds[anchor].size()) anchor = f;
      const Cloud c = in_object(clouds, anchor, to_object);
      // The registered frames next to the run (the part as it was just
      // before and just after), then a few dozen others, every few frames.
      std::vector<Eigen::Isometry3d> neighbours, registered;
      for (int f = begin - 1; f >= 0; --f)
        if (out->tracked[f]) {
          neighbours.push_back(to_model[f]);
          break;
        }
      for (int f = end; f < n; ++f)
        if (out->tracked[f]) {
          neighbours.push_back(to_model[f]);
          break;
        }
      for (int f = 0; f < n; ++f)
        if (out->tracked[f]) registered.push_back(to_model[f]);
      if (registered.size() > 24) {
        std::vector<Eigen::Isometry3d> some;
        for (size_t k = 0; k < registered.size(); k += registered.size() / 24) some.push_back(registered[k]);
        registered.swap(some);
      }
      registered.insert(registered.begin(), neighbours.begin(), neighbours.end());
      std::vector<IcpResult> fits;
      for (const Eigen::Isometry3d& start : reacquisition_starts(c, model, registered)) {
        IcpResult r = icp_point_to_plane(c, both_faces, both_tree, start, search);
        r = icp_point_to_plane(c, both_faces, both_tree, r.transform, fine);
        if (registered_well(r)) fits.push_back(r);
      }
      // A flat face fits itself turned about its normal as well as not.
      const IcpResult* chosen = nearest_of_the_best(fits, model, neighbours);
      if (chosen) {
        record(anchor, *chosen, true);
        last_good = anchor, before_last_good = -1;
        for (int f = anchor + 1; f < end; ++f) one_onto(f, both_faces, both_tree);
        last_good = anchor, before_last_good = -1;
        for (int f = anchor - 1; f >= begin; --f) one_onto(f, both_faces, both_tree);
      }
      begin = end + 1;
    }
  }
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
int reference_frame(const std::vector<Cloud>& clouds, const std::vector<Eigen::Isometry3d>& to_object) {
  const int n = static_cast<int>(clouds.size());
  std::vector<Eigen::Vector3d> centre(n, Eigen::Vector3d::Zero());
  std::vector<double> xs, ys, zs, counts;
  for (int f = 0; f < n; ++f) {
    const Cloud& c = clouds[f];
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
    if (clouds[f].size() >= kMinPoints) spread.push_back((centre[f] - typical).norm());
  // A part that moves spreads its centroids; twice the median distance
  // keeps its usual places and drops the strays.
  const double keep = std::max(0.02, 2.0 * median(spread));
  const double most = 2.0 * median(counts);
  int best = -1;
  size_t best_count = 0;
  for (int f = 0; f < n; ++f) {
    const size_t count = clouds[f].size();
    if (count < kMinPoints || (centre[f] - typical).norm() > keep || count > most) continue;
    if (count > best_count) best_count = count, best = f;
  }
  return best;
}

}  // namespace

Cloud part_cloud_in_object(const Observations& obs, int part, int frame,
                           const std::vector<Eigen::Isometry3d>& to_object) {
  return in_object(obs.parts[part].clouds, frame, to_object);
}

PartTrack track_part(const Observations& obs, int part, const std::vector<Eigen::Isometry3d>& to_object) {
  PartTrack out = track_clouds(obs.parts[part].clouds, to_object);
  out.part = part;
  return out;
}

PartTrack track_clouds(const std::vector<Cloud>& clouds, const std::vector<Eigen::Isometry3d>& to_object,
                       const TrackOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  PartTrack out;
  const int n = static_cast<int>(clouds.size());
  out.motion.assign(n, Eigen::Isometry3d::Identity());
  out.tracked.assign(n, false);
  out.rmse.assign(n, 0);
  out.inliers.assign(n, 0);
  out.conditioning.assign(n, 0);
  out.hessian.assign(n, Eigen::Matrix<double, 6, 6>::Zero());
  out.hessian_center.assign(n, Eigen::Vector3d::Zero());
  out.hessian_scale.assign(n, 0.0);
  out.reference_frame = reference_frame(clouds, to_object);
  if (out.reference_frame < 0) return out;

  // Pass 1: onto the reference frame's own points.
  Cloud model = in_object(clouds, out.reference_frame, to_object);
  register_frames(clouds, to_object, model, false, options, &out);
  // Pass 2: onto every tracked frame fused in the reference configuration
  // (a face seen only in frames found again, a lid's inside, is in it).
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
    Cloud c = in_object(clouds, f, to_object);
    transform_cloud(out.motion[f].inverse(), &c);
    fusion.add_frame(c);
  }
  Cloud fused = fusion.fused();
  if (fused.size() >= model.size() && fused.has_normals()) {
    model = std::move(fused);
    register_frames(clouds, to_object, model, true, options, &out);
  }
  out.model = std::move(model);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace efc::pipeline
