#include "synth/camera_path.h"

#include <algorithm>
#include <cmath>

#include "synth/image/rng.h"
#include "synth/timeline.h"

namespace efc::synth {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kTwoPi = 6.283185307179586;

// The wearer's eye is at a standing person's height (1.5-1.8 m over the
// camera_height knob's range), and always a little above the object's centre.
double eye_height_world(const Layout& L, const SceneKnobs& k) {
  const double c = L.center_world().z();
  return std::clamp(std::max(1.35 + 0.25 * k.camera_height, c + 0.25), 0.3, 2.2);
}

}  // namespace

Vector3d standing_eye(const Layout& L, const SceneKnobs& k) {
  // People stand at arm's length from what they operate, whatever its size:
  // the knob sets the gap between the eye and the object's front face.
  const double gap = std::clamp(k.camera_distance * 0.17, 0.3, 0.9);
  const Vector3d front(std::sin(k.camera_azimuth), -std::cos(k.camera_azimuth), 0);
  const double depth = 0.5 * (L.hi.y() - L.lo.y());
  Vector3d eye = L.center_object + (depth + gap) * front;
  // Heights are people's, in the world; the simulation frame differs from
  // the world by a rotation about z and a shift, so z maps by the shift.
  eye.z() = eye_height_world(L, k) - L.object_to_world.translation().z();
  return eye;
}

std::vector<CameraPose> plan_camera_path(const Layout& L, const SceneKnobs& k,
                                         const std::vector<Vector3d>& focus, double fps,
                                         double approach, uint64_t seed) {
  const int frames = static_cast<int>(focus.size());
  Rng rng(stream_seed(seed, 0x63616d, 0));  // "cam"
  const Vector3d stand = standing_eye(L, k);
  Vector3d away = stand - L.center_object;
  away.z() = 0;
  away = away.norm() > 1e-9 ? away.normalized() : Vector3d(0, -1, 0);
  const Vector3d start = stand + away * (0.8 + 0.5 * (stand - L.center_object).norm());
  // Slow wander: two incommensurate sines per angle, random phases.
  const double p1 = rng.uniform(0, kTwoPi), p2 = rng.uniform(0, kTwoPi), p3 = rng.uniform(0, kTwoPi),
               p4 = rng.uniform(0, kTwoPi), p5 = rng.uniform(0, kTwoPi);
  const double step_hz = rng.uniform(1.7, 2.1);
  const double duration = frames / fps;
  std::vector<double> turn_at, turn_by;
  for (int i = 0; i < k.fast_turns; ++i) {
    turn_at.push_back(rng.uniform(std::min(approach + 0.3, 0.8 * duration), 0.95 * duration));
    turn_by.push_back((rng.chance(0.5) ? 1 : -1) * rng.uniform(0.22, 0.38));
  }
  std::vector<CameraPose> path(frames);
  for (int f = 0; f < frames; ++f) {
    const double t = f / fps;
    const double walk = 1 - smoothstep(t / std::max(approach, 1e-6));  // 1 while walking, 0 standing
    const double arrived = 1 - std::pow(1 - std::min(1.0, t / std::max(approach, 1e-6)), 2);  // eases in
    Vector3d eye = start + (stand - start) * arrived;
    // Steps bob the head twice per stride; standing, breathing and balance sway it.
    const double bob = k.head_bob * (0.35 + 0.65 * walk);
    eye.z() += bob * std::sin(kTwoPi * step_hz * t + p1);
    eye += away.cross(Vector3d::UnitZ()) * (0.5 * bob * std::sin(0.5 * kTwoPi * step_hz * t + p2));
    double yaw = k.glance * (0.65 * std::sin(kTwoPi * 0.21 * t + p3) + 0.35 * std::sin(kTwoPi * 0.53 * t + p4));
    double pitch = 0.6 * k.glance * std::sin(kTwoPi * 0.29 * t + p5);
    for (size_t i = 0; i < turn_at.size(); ++i) {  // a quick look aside and back (~0.6 s)
      const double u = (t - turn_at[i]) / 0.3;
      if (std::fabs(u) < 1) yaw += turn_by[i] * 0.5 * (1 + std::cos(M_PI * u));
    }
    Rng jitter(stream_seed(seed, f, 0x6a6974));  // "jit": per frame, order-free
    yaw += k.jitter * jitter.normal();
    pitch += k.jitter * jitter.normal();
    const double roll = 0.02 * std::sin(kTwoPi * 0.17 * t + p2) + 0.5 * k.jitter * jitter.normal();

    Vector3d z = (focus[f] - eye).normalized();
    Vector3d x = z.cross(Vector3d::UnitZ());
    if (x.norm() < 1e-6) x = Vector3d::UnitX();
    x.normalize();
    Vector3d y = z.cross(x);
    Matrix3d R;
    R.col(0) = x, R.col(1) = y, R.col(2) = z;
    // Glances turn the head about the world's up axis and the camera's x.
    R = Eigen::AngleAxisd(yaw, Vector3d::UnitZ()).toRotationMatrix() * R *
        Eigen::AngleAxisd(pitch, Vector3d::UnitX()).toRotationMatrix() *
        Eigen::AngleAxisd(roll, Vector3d::UnitZ()).toRotationMatrix();
    path[f].position = eye;
    path[f].rotation = R;
  }
  return path;
}

Eigen::Quaterniond mujoco_camera_quat(const Matrix3d& cv) {
  Matrix3d mj;
  mj.col(0) = cv.col(0);
  mj.col(1) = -cv.col(1);
  mj.col(2) = -cv.col(2);
  return Eigen::Quaterniond(mj).normalized();
}

}  // namespace efc::synth
