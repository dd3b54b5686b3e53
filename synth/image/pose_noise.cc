// Camera-pose noise: what a visual(-inertial) odometry tracker reports.
// Its error has two parts with different physics:
//  - drift: each frame's small registration error is integrated, so the error
//    is a random walk whose spread grows with sqrt(time) (mild ~2 mm and
//    0.1 deg per sqrt(s), realistic ~1 cm and 0.5 deg per sqrt(s), per axis);
//  - jitter: the per-frame estimate's own white noise (mild 0.5 mm / 0.02 deg,
//    realistic 2 mm / 0.1 deg, per axis).
// Both are applied in the world frame, the rotation about the camera centre
// (so translation and rotation error are exactly their own parameters).
#include <cmath>

#include "synth/image/noise.h"

namespace efc::synth {
namespace {

using Quat = std::array<double, 4>;  // x y z w

Quat multiply(const Quat& a, const Quat& b) {
  return {a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
          a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
          a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
          a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
}

// The rotation by |v| radians about v.
Quat from_rotation_vector(const std::array<double, 3>& v) {
  double angle = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (angle < 1e-12) return {0.5 * v[0], 0.5 * v[1], 0.5 * v[2], 1.0};
  double s = std::sin(0.5 * angle) / angle;
  return {s * v[0], s * v[1], s * v[2], std::cos(0.5 * angle)};
}

Quat normalised(const Quat& q) {
  double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(n > 0)) return {0, 0, 0, 1};
  return {q[0] / n, q[1] / n, q[2] / n, q[3] / n};
}

}  // namespace

std::vector<seq::Pose> drift_poses(const NoiseParams& p, const std::vector<seq::Pose>& truth,
                                   uint64_t seed) {
  if (p.pose_walk_m == 0 && p.pose_walk_deg == 0 && p.pose_jitter_m == 0 &&
      p.pose_jitter_deg == 0) {
    return truth;
  }
  constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
  Rng rng(stream_seed(seed, 0, kPoseStream));  // a walk is sequential: one stream
  std::array<double, 3> walk_p{0, 0, 0}, walk_r{0, 0, 0};
  std::vector<seq::Pose> out;
  out.reserve(truth.size());
  for (size_t i = 0; i < truth.size(); ++i) {
    const seq::Pose& in = truth[i];
    double dt = i == 0 ? 0.0 : in.t - truth[i - 1].t;
    double sqrt_dt = dt > 0 && std::isfinite(dt) ? std::sqrt(dt) : 0.0;
    // Always the same number of draws per frame: frame i's numbers do not
    // depend on the times.
    std::array<double, 3> jitter_p, jitter_r;
    for (int a = 0; a < 3; ++a) {
      walk_p[a] += p.pose_walk_m * sqrt_dt * rng.normal();
      walk_r[a] += p.pose_walk_deg * kDegToRad * sqrt_dt * rng.normal();
      jitter_p[a] = p.pose_jitter_m * rng.normal();
      jitter_r[a] = p.pose_jitter_deg * kDegToRad * rng.normal();
    }
    seq::Pose pose = in;
    for (int a = 0; a < 3; ++a) pose.p[a] = in.p[a] + walk_p[a] + jitter_p[a];
    Quat q = multiply(from_rotation_vector(walk_r),
                      multiply(from_rotation_vector(jitter_r), normalised(in.q)));
    q = normalised(q);
    double same_side = q[0] * in.q[0] + q[1] * in.q[1] + q[2] * in.q[2] + q[3] * in.q[3];
    if (same_side < 0) q = {-q[0], -q[1], -q[2], -q[3]};  // q and -q: the truth's sign
    pose.q = q;
    out.push_back(pose);
  }
  return out;
}

}  // namespace efc::synth
