// The reconstruction stage (pipeline/infer/reconstruction.h) on made-up
// clouds: a cabinet on the floor, seen as a recording sees it. The far frames
// of the approach see all of its front, sparsely and each a little
// differently; the near frames see its top and the front's upper half
// densely. Its hull alone is a wedge missing the back and the foot; stood on
// its foot, it is the cabinet.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pipeline/cloud/mesh.h"
#include "pipeline/infer/reconstruction.h"

namespace {

using namespace efc::pipeline;
using Eigen::Vector3d;

// The cabinet: x in [-0.4, 0.4], y in [-0.25, 0.25] (its front at -0.25),
// z in [0, 0.7].
constexpr double kW = 0.8, kD = 0.5, kH = 0.7;

// Its front (y = -0.25) from z_lo up, and its top, on a grid of `step`
// metres; `noise` (m): each point off the surface by up to that much, as a
// depth camera's far readings are (frame `frame`'s own draw).
Cloud seen(double step, double z_lo, double noise, int frame) {
  Cloud c;
  unsigned state = 2654435761u * static_cast<unsigned>(frame + 1);
  auto jitter = [&]() {
    state = state * 1664525u + 1013904223u;
    return noise * (2.0 * (state >> 8) / double(1u << 24) - 1.0);
  };
  for (double x = -kW / 2; x <= kW / 2; x += step) {
    for (double z = z_lo; z <= kH; z += step) {
      c.points.emplace_back(x + jitter(), -kD / 2 + jitter(), z + jitter());
      c.normals.emplace_back(0, -1, 0);
    }
    for (double y = -kD / 2; y <= kD / 2; y += step) {
      c.points.emplace_back(x + jitter(), y + jitter(), kH + jitter());
      c.normals.emplace_back(0, 0, 1);
    }
  }
  return c;
}

Observations recording() {
  Observations obs;
  PartFrames body;
  body.name = "body";
  body.role = "object";
  // 10 far frames (points 1 cm apart, up to 5 mm off), then 30 near ones
  // (4 mm apart, exact) of the top and the front's upper half.
  for (int f = 0; f < 10; ++f) body.clouds.push_back(seen(0.01, 0.0, 0.005, f));
  for (int f = 0; f < 30; ++f) body.clouds.push_back(seen(0.004, 0.4, 0.0, f));
  body.pixels.assign(body.clouds.size(), 1000);
  obs.parts.push_back(body);
  for (size_t f = 0; f < obs.parts[0].clouds.size(); ++f) {
    obs.times.push_back(f / 30.0);
    obs.camera_to_world.push_back(Eigen::Isometry3d::Identity());
  }
  return obs;
}

TEST(PipelineInferReconstruction, ABodyStandsOnItsFoot) {
  const Observations obs = recording();
  const std::vector<Eigen::Isometry3d> to_object(obs.times.size(), Eigen::Isometry3d::Identity());
  PartReconstruction r = reconstruct_part(obs, 0, to_object, nullptr, nullptr);
  ASSERT_TRUE(r.ok) << r.error;
  const double box = kW * kD * kH;
  // The hull of the fine fusion: the top and the front down to where the
  // far frames' sparse, noisy points stop surviving it, a wedge without the
  // back or the foot.
  EXPECT_GT(r.bounds.min().z(), 0.1);
  EXPECT_LT(r.volume, 0.75 * box);
  const Eigen::AlignedBox3d fine_bounds = r.bounds;
  const size_t fine_points = r.fused.size();

  ASSERT_TRUE(stand_on_its_foot(obs, 0, to_object, &r));
  EXPECT_NEAR(r.volume, box, 0.05 * box);
  Eigen::AlignedBox3d stood;
  for (const Vector3d& v : r.mesh.vertices) stood.extend(v);
  EXPECT_NEAR(stood.min().z(), 0.0, 0.015);  // a coarse voxel's centroid
  EXPECT_NEAR(stood.max().z(), kH, 0.01);
  EXPECT_NEAR(stood.min().y(), -kD / 2, 0.01);
  EXPECT_NEAR(stood.max().y(), kD / 2, 0.01);
  // What the template stage reads stays as it was.
  EXPECT_EQ(r.fused.size(), fine_points);
  EXPECT_TRUE(r.bounds.isApprox(fine_bounds));
}

// A box seen from one corner (s0020's stove): two faces and the sliver of
// its top along them, turned 0.3 rad about the vertical. Stood on its
// foot, its hull is a prism over the hull of an L, half the box; squared,
// it is the box. A hood (two boxes), a box whose hull is the box already
// and a round body (a drum) keep their hulls.
TEST(PipelineInferReconstruction, ABoxSeenFromACornerIsSquared) {
  const double yaw = 0.3;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(yaw, Vector3d::UnitZ()).toRotationMatrix();
  PartReconstruction r;
  auto add = [&](const Vector3d& p, const Vector3d& n) {
    r.fused.points.push_back(turn * p);
    r.fused.normals.push_back(turn * n);
  };
  // Points 1 cm apart, the edges included (by count: a float step would
  // stop short of them).
  auto along = [](double lo, double hi) {
    std::vector<double> out;
    const int n = static_cast<int>(std::lround((hi - lo) / 0.01));
    for (int i = 0; i <= n; ++i) out.push_back(lo + (hi - lo) * i / n);
    return out;
  };
  for (double a : along(-kW / 2, kW / 2))
    for (double z : along(0, kH)) add({a, -kD / 2, z}, {0, -1, 0});  // front
  for (double b : along(-kD / 2, kD / 2))
    for (double z : along(0, kH)) add({kW / 2, b, z}, {1, 0, 0});  // right side
  for (double a : along(-kW / 2, kW / 2))
    for (double b : along(-kD / 2, kD / 2))
      if (b < -kD / 2 + 0.05 || a > kW / 2 - 0.05) add({a, b, kH}, {0, 0, 1});  // the top's sliver
  std::string error;
  ASSERT_TRUE(convex_hull(r.fused.points, &r.mesh, &error)) << error;
  r.volume = mesh_volume(r.mesh);
  const double box = kW * kD * kH;
  EXPECT_LT(r.volume, 0.6 * box);
  ASSERT_TRUE(square_the_body(&r));
  EXPECT_GT(r.box_share, 0.95);
  EXPECT_NEAR(r.volume, box, 0.03 * box);
  EXPECT_EQ(r.mesh.vertices.size(), 8u);
  for (const Vector3d& v : r.mesh.vertices) {
    const Vector3d local = turn.transpose() * v;
    EXPECT_NEAR(std::abs(local.x()), kW / 2, 0.005) << local.transpose();
    EXPECT_NEAR(std::abs(local.y()), kD / 2, 0.005) << local.transpose();
    EXPECT_TRUE(std::abs(local.z()) < 0.005 || std::abs(local.z() - kH) < 0.005) << local.transpose();
  }

  // A hood: a canopy and the chimney on it, every face upright or level.
  // What was seen of it lies inside the box of both (the chimney's front,
  // the canopy's top), not on its faces: not a box.
  PartReconstruction hood;
  auto face = [&](const Vector3d& corner, const Vector3d& a, const Vector3d& b, const Vector3d& n) {
    for (double i : along(0, 1))
      for (double j : along(0, 1)) {
        hood.fused.points.push_back(corner + i * a + j * b);
        hood.fused.normals.push_back(n);
      }
  };
  face({-0.3, -0.2, 0}, {0.6, 0, 0}, {0, 0, 0.06}, {0, -1, 0});        // canopy front
  face({-0.3, -0.2, 0.06}, {0.6, 0, 0}, {0, 0.19, 0}, {0, 0, 1});      // canopy top, before the chimney
  face({-0.1, -0.01, 0.06}, {0.2, 0, 0}, {0, 0, 0.39}, {0, -1, 0});    // chimney front
  face({0.1, -0.01, 0.06}, {0, 0.16, 0}, {0, 0, 0.39}, {1, 0, 0});     // chimney side
  face({-0.1, -0.01, 0.45}, {0.2, 0, 0}, {0, 0.16, 0}, {0, 0, 1});     // chimney top
  ASSERT_TRUE(convex_hull(hood.fused.points, &hood.mesh, &error)) << error;
  hood.volume = mesh_volume(hood.mesh);
  EXPECT_FALSE(square_the_body(&hood));
  EXPECT_GT(hood.box_share, 0.95);
  EXPECT_LT(hood.box_surface_share, kBoxSurfaceShare);

  // A box seen all round: its hull is the box already, and stays.
  PartReconstruction whole = r;
  whole.fused.points.clear(), whole.fused.normals.clear();
  for (const Vector3d& v : r.mesh.vertices) whole.fused.points.push_back(v);
  ASSERT_TRUE(convex_hull(whole.fused.points, &whole.mesh, &error)) << error;
  whole.fused = r.fused;
  whole.volume = mesh_volume(whole.mesh);
  EXPECT_FALSE(square_the_body(&whole));
  EXPECT_GT(whole.box_fill, kBoxFilled);

  PartReconstruction drum;
  const double radius = 0.3;
  for (double t = 0; t < 6.283; t += 0.02)
    for (double z : along(0, kH)) {
      drum.fused.points.emplace_back(radius * std::cos(t), radius * std::sin(t), z);
      drum.fused.normals.emplace_back(std::cos(t), std::sin(t), 0);
    }
  ASSERT_TRUE(convex_hull(drum.fused.points, &drum.mesh, &error)) << error;
  drum.volume = mesh_volume(drum.mesh);
  const size_t vertices = drum.mesh.vertices.size();
  EXPECT_FALSE(square_the_body(&drum));
  EXPECT_LT(drum.box_share, kBoxShare);
  EXPECT_EQ(drum.mesh.vertices.size(), vertices);
}

TEST(PipelineInferReconstruction, APartNeverSeenDoesNotStand) {
  Observations obs;
  PartFrames empty;
  empty.name = "bulb";
  empty.role = "object";
  empty.clouds.assign(5, Cloud{});
  empty.pixels.assign(5, 0);
  obs.parts.push_back(empty);
  obs.times = {0, 1, 2, 3, 4};
  obs.camera_to_world.assign(5, Eigen::Isometry3d::Identity());
  const std::vector<Eigen::Isometry3d> to_object(5, Eigen::Isometry3d::Identity());
  PartReconstruction r;
  EXPECT_FALSE(stand_on_its_foot(obs, 0, to_object, &r));
  EXPECT_TRUE(r.mesh.vertices.empty());
}

// A small knob (a 2 cm cube's faces) on a face, seen in 12 frames: in every
// third its mask was drawn too wide and took in the face around and behind
// it (a plate 1 cm behind, 3 cm across); in the others that plate lay in
// the mask's outline. The masks' vote drops the plate: the hull is the
// knob's. A part seen so little that its outline outvotes all of it keeps
// its unvoted mesh.
Cloud cube_faces(double half) {
  Cloud c;
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-1, 1})
      for (double u = -half; u <= half + 1e-9; u += 0.002)
        for (double v = -half; v <= half + 1e-9; v += 0.002) {
          Vector3d p, n = Vector3d::Zero();
          p[axis] = side * half, p[(axis + 1) % 3] = u, p[(axis + 2) % 3] = v;
          n[axis] = side;
          c.points.push_back(p), c.normals.push_back(n);
        }
  return c;
}

Cloud plate_behind() {
  Cloud c;
  for (double x = -0.015; x <= 0.015 + 1e-9; x += 0.002)
    for (double z = -0.015; z <= 0.015 + 1e-9; z += 0.002) c.points.emplace_back(x, 0.02, z), c.normals.emplace_back(0, -1, 0);
  return c;
}

Observations knob_recording(int frames, bool seen_plainly) {
  Observations obs;
  PartFrames knob;
  knob.name = "knob";
  knob.role = "receptor";
  for (int f = 0; f < frames; ++f) {
    const bool wide = f % 3 == 0;
    if (seen_plainly) {
      knob.clouds.push_back(wide ? concatenate(cube_faces(0.01), plate_behind()) : cube_faces(0.01));
      knob.outlines.push_back(wide ? Cloud{} : plate_behind());
    } else {
      // A speck (an 8 mm cube) in the wide frames only, in the outline in
      // the others, which see a stray point of the knob.
      Cloud speck = cube_faces(0.004), stray;
      for (Vector3d& p : speck.points) p.y() += 0.02;
      stray.points.emplace_back(1.0 + f, 0, 0), stray.normals.emplace_back(0, -1, 0);
      knob.clouds.push_back(wide ? speck : stray);
      knob.outlines.push_back(wide ? Cloud{} : speck);
    }
  }
  knob.pixels.assign(frames, 100);
  obs.parts.push_back(knob);
  for (int f = 0; f < frames; ++f) {
    obs.times.push_back(f / 30.0);
    obs.camera_to_world.push_back(Eigen::Isometry3d::Identity());
  }
  return obs;
}

TEST(PipelineInferReconstruction, TheMasksVoteKeepsWhatAMaskDrawnTooWideTookInOutOfTheMesh) {
  const Observations obs = knob_recording(12, true);
  const std::vector<Eigen::Isometry3d> to_object(obs.times.size(), Eigen::Isometry3d::Identity());
  const PartReconstruction r = reconstruct_part(obs, 0, to_object, nullptr, nullptr);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_GT(r.outline_dropped, 100);
  EXPECT_LT(r.bounds.max().y(), 0.012);  // the cube's back face, not the plate 1 cm behind it
  EXPECT_NEAR(r.volume, 8e-6, 2e-6);
  // Without the outlines, the plate stays.
  Observations blind = obs;
  blind.parts[0].outlines.clear();
  const PartReconstruction plain = reconstruct_part(blind, 0, to_object, nullptr, nullptr);
  ASSERT_TRUE(plain.ok) << plain.error;
  EXPECT_EQ(plain.outline_dropped, 0);
  EXPECT_GT(plain.bounds.max().y(), 0.018);

  const Observations glimpsed = knob_recording(12, false);
  const PartReconstruction kept = reconstruct_part(glimpsed, 0, to_object, nullptr, nullptr);
  ASSERT_TRUE(kept.ok) << kept.error;
  EXPECT_EQ(kept.outline_dropped, 0);
  EXPECT_GT(kept.fused.size(), 20u);
}

}  // namespace
