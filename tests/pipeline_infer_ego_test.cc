// efc infer's camera registration (stage 2) and what it registers on: the
// room beside the object fixes what one plane of it cannot (a turn about
// the plane's normal, a slide along it), and the room's points are the
// pixels no mask claims, near enough for the depth to be good.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "pipeline/cloud/depth_points.h"
#include "pipeline/infer/ego_anchor.h"
#include "pipeline/infer/ego_motion.h"
#include "pipeline/infer/observations.h"
#include "sequence/sequence.h"

namespace {

using namespace efc::pipeline;
using Eigen::Vector3d;
constexpr double kPi = 3.14159265358979323846;

// A rectangle of points 1 cm apart: corner + i u + j v, normal n.
void add_rectangle(const Vector3d& corner, const Vector3d& u, const Vector3d& v, const Vector3d& n, Cloud* c) {
  const int nu = static_cast<int>(u.norm() / 0.01), nv = static_cast<int>(v.norm() / 0.01);
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      c->points.push_back(corner + u * i / nu + v * j / nv);
      c->normals.push_back(n);
    }
}

// The world as it is: an object's front face (the plane y = 0, facing -y, as
// a camera close to a fridge sees it) and the room: the floor, and a cabinet
// side to its right.
Cloud front_face() {
  Cloud c;
  add_rectangle({-0.2, 0, 0.1}, {0.4, 0, 0}, {0, 0, 0.5}, {0, -1, 0}, &c);
  return c;
}
Cloud room() {
  Cloud c;
  add_rectangle({-0.8, -0.8, 0}, {1.6, 0, 0}, {0, 1.0, 0}, {0, 0, 1}, &c);      // floor
  add_rectangle({0.5, -0.6, 0.02}, {0, 0.8, 0}, {0, 0, 0.8}, {-1, 0, 0}, &c);   // cabinet side
  return c;
}

// The tracker's error in frame f: none in the first second (drift starts at
// zero), then a turn of 1.5 degrees about the face's normal and a slide of
// 1 cm along it.
Eigen::Isometry3d tracker_error(int f) {
  Eigen::Isometry3d E = Eigen::Isometry3d::Identity();
  if (f < 30) return E;
  const double s = std::min(1.0, (f - 30) / 10.0);
  E.linear() = Eigen::AngleAxisd(s * 1.5 * kPi / 180, Vector3d::UnitY()).toRotationMatrix();
  E.translation() = s * Vector3d(0.01, 0, 0.005);
  return E;
}

// Frames of a still scene whose clouds the tracker's error has moved: each
// frame's points are E_f^-1 (truth) plus 1 mm of noise, so the right
// correction of frame f is E_f.
Observations recording(bool with_room) {
  Observations obs;
  const int n = 60;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 0.001);
  auto seen = [&](const Cloud& truth, int f) {
    Cloud c = truth;
    for (Vector3d& p : c.points) p += Vector3d(noise(rng), noise(rng), noise(rng));
    transform_cloud(tracker_error(f).inverse(), &c);
    return c;
  };
  PartFrames body;
  body.name = "body";
  body.role = "object";
  const Cloud face = front_face(), scene = room();
  for (int f = 0; f < n; ++f) {
    obs.times.push_back(f / 30.0);
    obs.camera_to_world.push_back(Eigen::Isometry3d::Identity());
    body.clouds.push_back(seen(face, f));
    body.pixels.push_back(static_cast<int>(face.size()));
    obs.background.push_back(with_room ? seen(scene, f) : Cloud{});
  }
  obs.parts.push_back(std::move(body));
  return obs;
}

// The largest error over the frames of the corrections against E_f: angle
// (degrees) and translation at the face's centre (m).
void worst_error(const EgoMotion& ego, double* degrees, double* metres) {
  *degrees = 0, *metres = 0;
  const Vector3d centre(0, 0, 0.35);
  for (size_t f = 0; f < ego.correction.size(); ++f) {
    const Eigen::Isometry3d residual = tracker_error(static_cast<int>(f)) * ego.correction[f].inverse();
    *degrees = std::max(*degrees, Eigen::AngleAxisd(residual.rotation()).angle() * 180 / kPi);
    *metres = std::max(*metres, (residual * centre - centre).norm());
  }
}

TEST(PipelineInferEgo, TheRoomFixesTheTurnAndSlideOnePlaneCannotShow) {
  double degrees = 0, metres = 0;
  // The object alone: its front face says nothing of a turn about its
  // normal, so the tracker's 1.5 degrees stay.
  const EgoMotion alone = refine_ego_motion(recording(false), {0}, 1, nullptr);
  worst_error(alone, &degrees, &metres);
  EXPECT_GT(degrees, 1.0);
  // With the floor and the cabinet beside it, the turn and the slide are
  // found: the corrections are the tracker's errors.
  const EgoMotion with_room = refine_ego_motion(recording(true), {0}, 1, nullptr);
  worst_error(with_room, &degrees, &metres);
  EXPECT_LT(degrees, 0.1);
  EXPECT_LT(metres, 0.002);
  for (bool registered : with_room.registered) EXPECT_TRUE(registered);
  // The model handed on is the object's, not the room's: nothing of it lies
  // on the floor or beyond the face.
  ASSERT_GT(with_room.model.size(), 100u);
  for (const Vector3d& p : with_room.model.points) {
    EXPECT_GT(p.z(), 0.09);
    EXPECT_LT(std::abs(p.y()), 0.01);
  }
}

// A box's front face and the floor leave a slide along both free; a spout
// on the face (an effector, registered on at a fraction of the body's
// weight) holds it. Seed 1's s0018 of the synthetic suite: the tracker's
// drift along the face stayed in the camera (4 cm) until the spout counted.
Cloud spout() {  // a 6 cm cube standing out of the face at x = 0.1
  Cloud c;
  add_rectangle({0.07, -0.06, 0.3}, {0, 0.06, 0}, {0, 0, 0.06}, {-1, 0, 0}, &c);
  add_rectangle({0.13, -0.06, 0.3}, {0, 0.06, 0}, {0, 0, 0.06}, {1, 0, 0}, &c);
  add_rectangle({0.07, -0.06, 0.3}, {0.06, 0, 0}, {0, 0, 0.06}, {0, -1, 0}, &c);
  return c;
}

// The tracker's error in frame f: none in the first second, then a slide
// of 1.5 cm along the face.
Eigen::Isometry3d slide_error(int f) {
  Eigen::Isometry3d E = Eigen::Isometry3d::Identity();
  E.translation() = Vector3d(0.015 * std::clamp((f - 30) / 10.0, 0.0, 1.0), 0, 0);
  return E;
}

// Frames seen through slide_error; an effector that moves (`lid_moves`)
// slides 5 mm along x itself from frame 40 on (near enough for its points
// to stay pairs: it pulls).
Observations slide_recording(bool cabinet, bool lid_moves) {
  Observations obs;
  const int n = 60;
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0, 0.001);
  auto seen = [&](Cloud c, int f, const Vector3d& moved) {
    for (Vector3d& p : c.points) p += moved + Vector3d(noise(rng), noise(rng), noise(rng));
    transform_cloud(slide_error(f).inverse(), &c);
    return c;
  };
  Cloud floor;
  add_rectangle({-0.5, -0.6, 0}, {1.0, 0, 0}, {0, 0.6, 0}, {0, 0, 1}, &floor);
  if (cabinet) add_rectangle({0.5, -0.6, 0.02}, {0, 0.6, 0}, {0, 0, 0.5}, {-1, 0, 0}, &floor);
  PartFrames body, effector;
  body.name = "body", body.role = "object";
  effector.name = "spout", effector.role = "effector";
  const Cloud face = front_face(), outlet = spout();
  for (int f = 0; f < n; ++f) {
    obs.times.push_back(f / 30.0);
    obs.camera_to_world.push_back(Eigen::Isometry3d::Identity());
    body.clouds.push_back(seen(face, f, Vector3d::Zero()));
    body.pixels.push_back(static_cast<int>(face.size()));
    effector.clouds.push_back(seen(outlet, f, Vector3d(lid_moves && f >= 40 ? 0.005 : 0.0, 0, 0)));
    effector.pixels.push_back(static_cast<int>(outlet.size()));
    obs.background.push_back(seen(floor, f, Vector3d::Zero()));
  }
  obs.parts.push_back(std::move(body));
  obs.parts.push_back(std::move(effector));
  return obs;
}

// The largest translation error over the frames at the face's centre (m).
double worst_slide(const EgoMotion& ego) {
  double worst = 0;
  const Vector3d centre(0, 0, 0.35);
  for (size_t f = 0; f < ego.correction.size(); ++f) {
    const Eigen::Isometry3d residual = slide_error(static_cast<int>(f)) * ego.correction[f].inverse();
    worst = std::max(worst, (residual * centre - centre).norm());
  }
  return worst;
}

TEST(PipelineInferEgo, AStillEffectorHoldsTheSlideTheBodyAndFloorLeaveFree) {
  // The body and the floor alone: the 1.5 cm slide along the face stays.
  EXPECT_GT(worst_slide(refine_ego_motion(slide_recording(false, false), {0}, 1, nullptr)), 0.01);
  // The spout registered on as well: the slide is found.
  const EgoMotion held = refine_ego_motion(slide_recording(false, false), {0}, 1, nullptr, {1});
  EXPECT_LT(worst_slide(held), 0.002);
  // The model handed on is still the body's alone: nothing stands out of
  // the face where the spout is.
  for (const Vector3d& p : held.model.points) EXPECT_LT(std::abs(p.y()), 0.01);
}

TEST(PipelineInferEgo, AnEffectorThatMovesPullsLittleWhereTheBodyHoldsTheCamera) {
  // With a cabinet side beside it the room fixes the slide; the spout then
  // sliding 5 mm itself barely moves the camera (its share is small).
  EXPECT_LT(worst_slide(refine_ego_motion(slide_recording(true, true), {0}, 1, nullptr, {1})), 0.002);
}

// The room's points of a committed synthetic recording are the pixels no
// part's or the hand's mask claims, nearer than background_max_depth.
TEST(PipelineInferEgo, TheRoomIsWhatNoMaskClaims) {
  const std::string dir =
      std::string(EFC_SOURCE_DIR) + "/tests/data/synth-suite/s0000_binary-illumination_revolute/seq";
  efc::Diagnostics diags;
  efc::seq::Sequence sequence;
  ASSERT_TRUE(sequence.open(dir, diags));
  ObserveOptions options;
  options.threads = 1;
  Observations obs;
  ASSERT_TRUE(observe(sequence, options, diags, nullptr, &obs));
  ASSERT_EQ(obs.background.size(), obs.times.size());
  const efc::seq::Meta& meta = sequence.meta();
  int frames_with_room = 0;
  for (size_t f = 0; f < obs.background.size(); ++f) {
    const Cloud& room_points = obs.background[f];
    frames_with_room += !room_points.points.empty();
    std::vector<efc::seq::Image8> masks;
    for (const std::string& name : sequence.mask_names()) {
      masks.emplace_back();
      ASSERT_TRUE(sequence.read_mask(name, static_cast<int>(f), diags, &masks.back()));
    }
    const Eigen::Isometry3d world_to_camera = obs.camera_to_world[f].inverse();
    for (const Vector3d& p : room_points.points) {
      const Vector3d q = world_to_camera * p;
      EXPECT_LE(q.z(), options.background_max_depth + 1e-6);
      double u = 0, v = 0;
      ASSERT_TRUE(project(meta.intrinsics, q, &u, &v));
      const int x = static_cast<int>(std::lround(u)), y = static_cast<int>(std::lround(v));
      ASSERT_TRUE(x >= 0 && y >= 0 && x < meta.width && y < meta.height);
      for (const efc::seq::Image8& m : masks)
        ASSERT_EQ(m.pixels[static_cast<size_t>(y) * m.width + x], 0) << "frame " << f << " pixel " << x << "," << y;
    }
  }
  EXPECT_GT(frames_with_room, static_cast<int>(obs.times.size()) / 2);

  // Each part's outline: points just outside its mask (within
  // kOutlinePixels of it, never in it), the pixels a mask drawn a little too
  // wide would have taken in.
  int outline_points = 0;
  for (const PartFrames& pf : obs.parts) {
    ASSERT_EQ(pf.outlines.size(), obs.times.size());
    for (size_t f = 0; f < pf.outlines.size(); ++f) {
      if (pf.outlines[f].points.empty()) continue;
      efc::seq::Image8 mask;
      ASSERT_TRUE(sequence.read_mask(pf.mask, static_cast<int>(f), diags, &mask));
      const Eigen::Isometry3d world_to_camera = obs.camera_to_world[f].inverse();
      for (const Vector3d& p : pf.outlines[f].points) {
        double u = 0, v = 0;
        ASSERT_TRUE(project(meta.intrinsics, world_to_camera * p, &u, &v));
        const int x = static_cast<int>(std::lround(u)), y = static_cast<int>(std::lround(v));
        ASSERT_EQ(mask.pixels[static_cast<size_t>(y) * mask.width + x], 0) << pf.name << " frame " << f;
        bool near = false;
        for (int dy = -kOutlinePixels; dy <= kOutlinePixels && !near; ++dy)
          for (int dx = -kOutlinePixels; dx <= kOutlinePixels && !near; ++dx) {
            const int xx = x + dx, yy = y + dy;
            near = xx >= 0 && yy >= 0 && xx < mask.width && yy < mask.height &&
                   mask.pixels[static_cast<size_t>(yy) * mask.width + xx] != 0;
          }
        ASSERT_TRUE(near) << pf.name << " frame " << f << " pixel " << x << "," << y;
        ++outline_points;
      }
    }
  }
  EXPECT_GT(outline_points, 1000);

  // Off, there is none.
  options.background = false;
  ASSERT_TRUE(observe(sequence, options, diags, nullptr, &obs));
  for (const Cloud& c : obs.background) EXPECT_TRUE(c.points.empty());
}

// The anchor (ego_anchor.h): a tracker whose error is a random walk from
// zero plus jitter, as efc synth's "realistic" poses (1 cm and 0.5 degrees
// per sqrt(s), 2 mm and 0.1 degrees), the rotation about a camera 2.5 m
// from the object. Frame f's correction is C_f = A^-1 D_f^-1 for the true
// model-to-world A. The anchor finds A within a few millimetres at the
// object, where the first second's mean correction was centimetres off, and
// reads the noise off the corrections.
struct TrackerNoise {
  double walk_m, walk_rad, jitter_m, jitter_rad;
};

std::vector<Eigen::Isometry3d> tracker_errors(const TrackerNoise& noise, int frames, double fps, const Vector3d& camera,
                                              unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0, 1);
  auto draw = [&](double s) { return Vector3d(s * normal(rng), s * normal(rng), s * normal(rng)); };
  Vector3d walk_p = Vector3d::Zero(), walk_r = Vector3d::Zero();
  std::vector<Eigen::Isometry3d> out;
  for (int f = 0; f < frames; ++f) {
    if (f > 0) {
      walk_p += draw(noise.walk_m / std::sqrt(fps));
      walk_r += draw(noise.walk_rad / std::sqrt(fps));
    }
    const Vector3d r = walk_r + draw(noise.jitter_rad), p = walk_p + draw(noise.jitter_m);
    Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
    D.linear() = Eigen::AngleAxisd(r.norm(), r.norm() > 0 ? Vector3d(r.normalized()) : Vector3d::UnitZ()).toRotationMatrix();
    D.translation() = camera - D.linear() * camera + p;  // about the camera's centre
    out.push_back(D);
  }
  return out;
}

TEST(PipelineInferEgo, TheAnchorWeighsTheFirstFramesByTheTrackersNoise) {
  const TrackerNoise realistic{0.01, 0.5 * kPi / 180, 0.002, 0.1 * kPi / 180};
  const int n = 150;
  const double fps = 30;
  const Vector3d centre(0.1, 0.2, 0.9), camera(2.0, -1.2, 1.6);
  Eigen::Isometry3d A = Eigen::Isometry3d::Identity();
  A.linear() = Eigen::AngleAxisd(0.3, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  A.translation() = Vector3d(0.5, -0.2, 0.1);
  std::vector<double> times;
  for (int f = 0; f < n; ++f) times.push_back(f / fps);
  double new_sum = 0, old_sum = 0, jitter_sum = 0, walk_sum = 0;
  const int trials = 20;
  for (int trial = 0; trial < trials; ++trial) {
    const auto D = tracker_errors(realistic, n, fps, camera, 100 + trial);
    std::vector<Eigen::Isometry3d> C;
    for (const Eigen::Isometry3d& d : D) C.push_back(A.inverse() * d.inverse());
    std::vector<bool> registered(n, true);
    registered[0] = registered[3] = false;  // a frame or two unregistered
    const Vector3d model_centre = A.inverse() * centre;
    const EgoAnchor anchor = anchor_refined_world(times, C, registered, model_centre);
    new_sum += (anchor.model_to_world * model_centre - centre).norm();
    jitter_sum += anchor.jitter_m;
    walk_sum += anchor.walk_m_per_sqrt_s;
    // What it replaces: the mean correction over the first second.
    std::vector<Eigen::Isometry3d> early;
    for (int f = 0; f < n && times[f] <= 1.0; ++f)
      if (registered[f]) early.push_back(C[f]);
    old_sum += (mean_transform(early).inverse() * model_centre - centre).norm();
  }
  const double new_error = new_sum / trials, old_error = old_sum / trials;
  EXPECT_LT(new_error, 0.01);  // 7.9 mm, frame 0 unregistered
  EXPECT_LT(new_error, 0.5 * old_error);  // 18.5 mm
  // The noise at the centre, per axis: a turn about the camera 2.46 m away
  // moves it by sqrt(2/3) 2.46 m times the angle on average, so the jitter
  // is 2 mm and 3.5 mm together, 4.0 mm, and the walk 1 cm and 1.75 cm
  // per sqrt(s), 2.0 cm.
  EXPECT_NEAR(jitter_sum / trials, 0.0040, 0.0008);
  EXPECT_NEAR(walk_sum / trials, 0.020, 0.005);
}

TEST(PipelineInferEgo, TheAnchorWeighsEveryFrameAlikeWhereNothingDrifts) {
  const TrackerNoise jitter_only{0, 0, 0.003, 0};
  const int n = 120;
  const Vector3d centre(0, 0, 0.5), camera(0, -2, 1.5);
  std::vector<double> times;
  for (int f = 0; f < n; ++f) times.push_back(f / 30.0);
  const auto D = tracker_errors(jitter_only, n, 30, camera, 5);
  std::vector<Eigen::Isometry3d> C;
  for (const Eigen::Isometry3d& d : D) C.push_back(d.inverse());
  const EgoAnchor anchor = anchor_refined_world(times, C, std::vector<bool>(n, true), centre);
  EXPECT_EQ(anchor.frames, n);
  EXPECT_NEAR(anchor.weight_first_second, 30.0 / n, 0.05);
  // The mean of 120 frames: 3 mm / sqrt(120) per axis.
  EXPECT_LT((anchor.model_to_world * centre - centre).norm(), 0.0015);
  // None registered: the identity.
  const EgoAnchor none = anchor_refined_world(times, C, std::vector<bool>(n, false), centre);
  EXPECT_TRUE(none.model_to_world.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(none.frames, 0);
}

}  // namespace
