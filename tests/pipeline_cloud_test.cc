// The point-cloud primitives of `efc infer` (pipeline/cloud/): each test
// builds a scene with a known answer (a plane's depth image, a box moved by a
// known transform, a cube's hull) and checks the primitive recovers it.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#include "pipeline/cloud/cloud.h"
#include "pipeline/cloud/depth_points.h"
#include "pipeline/cloud/filters.h"
#include "pipeline/cloud/fusion.h"
#include "pipeline/cloud/icp.h"
#include "pipeline/cloud/kdtree.h"
#include "pipeline/cloud/mesh.h"

namespace efc::pipeline {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Uniform samples on the surface of an axis-aligned box centred at the origin,
// with outward normals.
Cloud sample_box(const Eigen::Vector3d& size, int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const double ax = size.y() * size.z(), ay = size.x() * size.z(), az = size.x() * size.y();
  std::uniform_real_distribution<double> pick(0, ax + ay + az);
  Cloud c;
  for (int i = 0; i < n; ++i) {
    const double r = pick(rng);
    const int axis = r < ax ? 0 : (r < ax + ay ? 1 : 2);
    const double sign = (rng() & 1) ? 1.0 : -1.0;
    Eigen::Vector3d p(u(rng) * size.x(), u(rng) * size.y(), u(rng) * size.z());
    p[axis] = sign * size[axis] / 2;
    Eigen::Vector3d nrm = Eigen::Vector3d::Zero();
    nrm[axis] = sign;
    c.points.push_back(p);
    c.normals.push_back(nrm);
  }
  return c;
}

// The lateral surface of a cylinder about z (open: no caps), outward normals.
Cloud sample_cylinder(double radius, double height, int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(0, 2 * kPi), h(-height / 2, height / 2);
  Cloud c;
  for (int i = 0; i < n; ++i) {
    const double a = angle(rng);
    c.points.emplace_back(radius * std::cos(a), radius * std::sin(a), h(rng));
    c.normals.emplace_back(std::cos(a), std::sin(a), 0);
  }
  return c;
}

void add_noise(Cloud* c, double sigma, std::mt19937& rng) {
  std::normal_distribution<double> g(0, sigma);
  for (auto& p : c->points) p += Eigen::Vector3d(g(rng), g(rng), g(rng));
}

double angle_deg(const Eigen::Matrix3d& R) {
  return Eigen::AngleAxisd(R).angle() * 180 / kPi;
}

// ---- cloud.h

TEST(PipelineCloud, TransformMovesPointsAndRotatesNormals) {
  Cloud c;
  c.points = {{1, 0, 0}};
  c.normals = {{1, 0, 0}};
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0, 0, 2);
  transform_cloud(T, &c);
  EXPECT_LT((c.points[0] - Eigen::Vector3d(0, 1, 2)).norm(), 1e-12);
  EXPECT_LT((c.normals[0] - Eigen::Vector3d(0, 1, 0)).norm(), 1e-12);  // not translated
}

TEST(PipelineCloud, ConcatenateKeepsNormalsOnlyWhenAllHaveThem) {
  Cloud a, b, empty;
  a.points = {{0, 0, 0}};
  a.normals = {{0, 0, 1}};
  b.points = {{1, 0, 0}, {2, 0, 0}};
  EXPECT_EQ(concatenate(a, b).size(), 3u);
  EXPECT_FALSE(concatenate(a, b).has_normals());
  EXPECT_TRUE(concatenate(a, empty).has_normals());
  EXPECT_TRUE(concatenate(a, a).has_normals());
}

// ---- depth_points.h

struct PlaneScene {
  seq::Intrinsics K{300, 300, 79.5, 59.5};
  seq::Image16 depth;
  Eigen::Vector3d n;  // plane n . X = d in the camera frame
  double d = 0;
  double scale = 0.0001;  // 0.1 mm per unit
};

PlaneScene tilted_plane() {
  PlaneScene s;
  s.n = Eigen::Vector3d(0.3, -0.2, -1).normalized();  // facing the camera
  s.d = -0.8;
  s.depth.width = 160;
  s.depth.height = 120;
  s.depth.pixels.resize(160 * 120);
  for (int v = 0; v < 120; ++v)
    for (int u = 0; u < 160; ++u) {
      const Eigen::Vector3d ray((u - s.K.cx) / s.K.fx, (v - s.K.cy) / s.K.fy, 1);
      const double z = s.d / s.n.dot(ray);
      s.depth.pixels[v * 160 + u] = static_cast<uint16_t>(std::lround(z / s.scale));
    }
  return s;
}

TEST(PipelineCloud, BackprojectPlaneGivesPointsOnItWithItsNormal) {
  const PlaneScene s = tilted_plane();
  BackprojectOptions o;
  const Cloud c = backproject(s.depth, s.scale, s.K, nullptr, o);
  ASSERT_EQ(c.size(), 158u * 118u);  // all but the 1-pixel border (its neighbours are missing)
  ASSERT_TRUE(c.has_normals());
  double worst_dist = 0, worst_angle = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    worst_dist = std::max(worst_dist, std::abs(s.n.dot(c.points[i]) - s.d));
    worst_angle = std::max(worst_angle, std::acos(std::min(1.0, c.normals[i].dot(s.n))) * 180 / kPi);
    EXPECT_LT(c.normals[i].dot(c.points[i]), 0);
  }
  EXPECT_LT(worst_dist, 1e-4);   // depth quantisation (0.1 mm units)
  EXPECT_LT(worst_angle, 2.0);   // normals from 0.1 mm-quantised neighbours

  // Every point projects back to its pixel (a pixel-grid point).
  double u = 0, v = 0;
  ASSERT_TRUE(project(s.K, c.points[0], &u, &v));
  EXPECT_NEAR(u, std::round(u), 1e-6);
  EXPECT_NEAR(v, std::round(v), 1e-6);
  EXPECT_FALSE(project(s.K, Eigen::Vector3d(0, 0, -1), &u, &v));

  o.stride = 4;
  const Cloud sparse = backproject(s.depth, s.scale, s.K, nullptr, o);
  EXPECT_EQ(sparse.size(), 38u * 28u);  // u in 4..152, v in 4..112 (+/-4 inside the image)
}

TEST(PipelineCloud, BackprojectHonoursMaskAndDropsDepthEdges) {
  PlaneScene s = tilted_plane();
  // A step: the right half 30 cm nearer (an occluding object), and one mixed
  // pixel column between them.
  for (int v = 0; v < 120; ++v) {
    for (int u = 80; u < 160; ++u) s.depth.pixels[v * 160 + u] -= 3000;
    s.depth.pixels[v * 160 + 80] += 1500;
  }
  seq::Image8 mask;
  mask.width = 160;
  mask.height = 120;
  mask.channels = 1;
  mask.pixels.assign(160 * 120, 0);
  for (int v = 0; v < 60; ++v)
    for (int u = 0; u < 160; ++u) mask.pixels[v * 160 + u] = 255;
  const Cloud c = backproject(s.depth, s.scale, s.K, &mask, BackprojectOptions{});
  ASSERT_GT(c.size(), 0u);
  for (const auto& p : c.points) {
    double u = 0, v = 0;
    ASSERT_TRUE(project(s.K, p, &u, &v));
    EXPECT_LT(v, 59.5);                              // inside the mask
    EXPECT_TRUE(u < 78.5 || u > 81.5) << "u=" << u;  // no point at the step
  }
  // Without normals the step still drops the pixels either side of it.
  BackprojectOptions no_normals;
  no_normals.normals = false;
  const Cloud plain = backproject(s.depth, s.scale, s.K, &mask, no_normals);
  EXPECT_FALSE(plain.has_normals());
  EXPECT_EQ(plain.size(), 60u * 157u);  // every masked row loses columns 79, 80, 81
}

TEST(PipelineCloud, BackprojectBadInputGivesEmpty) {
  PlaneScene s = tilted_plane();
  seq::Image16 zero = s.depth;
  std::fill(zero.pixels.begin(), zero.pixels.end(), 0);
  EXPECT_EQ(backproject(zero, s.scale, s.K, nullptr, {}).size(), 0u);
  seq::Image8 small;
  small.width = 10;
  small.height = 10;
  small.channels = 1;
  small.pixels.assign(100, 255);
  EXPECT_EQ(backproject(s.depth, s.scale, s.K, &small, {}).size(), 0u);
  seq::Intrinsics bad = s.K;
  bad.fx = 0;
  EXPECT_EQ(backproject(s.depth, s.scale, bad, nullptr, {}).size(), 0u);
  seq::Image16 broken = s.depth;
  broken.pixels.resize(5);
  EXPECT_EQ(backproject(broken, s.scale, s.K, nullptr, {}).size(), 0u);
  EXPECT_EQ(backproject(s.depth, kNaN, s.K, nullptr, {}).size(), 0u);
  BackprojectOptions far;
  far.min_depth = 5;  // the plane is nearer than that
  EXPECT_EQ(backproject(s.depth, s.scale, s.K, nullptr, far).size(), 0u);
}

// ---- kdtree.h

TEST(PipelineCloud, KdTreeAgreesWithBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Vector3d> pts(2000);
  for (auto& p : pts) p = Eigen::Vector3d(u(rng), u(rng), u(rng));
  pts[17] = Eigen::Vector3d(kNaN, 0, 0);  // left out of the tree
  KdTree tree(pts);
  EXPECT_EQ(tree.size(), 1999u);
  for (int q = 0; q < 50; ++q) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    std::vector<std::pair<double, size_t>> brute;
    for (size_t i = 0; i < pts.size(); ++i)
      if (pts[i].allFinite()) brute.emplace_back((pts[i] - x).squaredNorm(), i);
    std::sort(brute.begin(), brute.end());
    size_t idx = 0;
    double d2 = 0;
    ASSERT_TRUE(tree.nearest(x, &idx, &d2));
    EXPECT_EQ(idx, brute[0].second);
    EXPECT_NEAR(d2, brute[0].first, 1e-12);
    std::vector<size_t> knn;
    std::vector<double> kd2;
    tree.knn(x, 5, &knn, &kd2);
    ASSERT_EQ(knn.size(), 5u);
    for (int k = 0; k < 5; ++k) EXPECT_EQ(knn[k], brute[k].second);
    std::vector<size_t> within;
    tree.radius(x, 0.2, &within);
    size_t expected = 0;
    while (expected < brute.size() && brute[expected].first < 0.04) ++expected;
    EXPECT_EQ(within.size(), expected);
    // The nearest within a distance: the nearest where it is that near,
    // none where it is not (0.04 and 0.08 squared, about the nearest's
    // distance among 2000 points in the cube).
    for (double r : {0.04, 0.08}) {
      size_t near_idx = 0;
      double near_d2 = 0;
      const bool found = tree.nearest_within(x, r, &near_idx, &near_d2);
      EXPECT_EQ(found, brute[0].first < r * r) << r;
      if (found) {
        EXPECT_EQ(near_idx, brute[0].second);
        EXPECT_NEAR(near_d2, brute[0].first, 1e-12);
      }
    }
  }
  std::vector<Eigen::Vector3d> none;
  KdTree empty(none);
  size_t idx = 0;
  double d2 = 0;
  EXPECT_FALSE(empty.nearest(Eigen::Vector3d::Zero(), &idx, &d2));
  std::vector<size_t> out{1, 2};
  empty.knn(Eigen::Vector3d::Zero(), 3, &out, nullptr);
  EXPECT_TRUE(out.empty());
  EXPECT_FALSE(tree.nearest(Eigen::Vector3d(kNaN, 0, 0), &idx, &d2));
  EXPECT_FALSE(empty.nearest_within(Eigen::Vector3d::Zero(), 1.0, &idx, &d2));
  EXPECT_FALSE(tree.nearest_within(Eigen::Vector3d(kNaN, 0, 0), 1.0, &idx, &d2));
  EXPECT_FALSE(tree.nearest_within(Eigen::Vector3d::Zero(), 0.0, &idx, &d2));
}

// ---- icp.h

TEST(PipelineCloud, IcpRecoversRigidMotionOfNoisyBoxWithOutliers) {
  std::mt19937 rng(42);
  const Eigen::Vector3d size(0.2, 0.15, 0.1);
  const Cloud target = sample_box(size, 5000, rng);
  Cloud source = sample_box(size, 5000, rng);  // other samples of the same surface
  add_noise(&source, 0.0005, rng);
  // 20% outliers: uniform around the box.
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  for (int i = 0; i < 1250; ++i) source.points.emplace_back(u(rng), u(rng), u(rng));
  source.normals.clear();

  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.linear() = Eigen::AngleAxisd(10 * kPi / 180, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  truth.translation() = Eigen::Vector3d(0.02, -0.015, 0.0173);  // 3 cm
  transform_cloud(truth.inverse(), &source);  // so `truth` maps source onto target

  KdTree tree(target.points);
  IcpOptions o;
  o.max_correspondence = 0.05;  // the start is up to ~5 cm off
  const auto t0 = std::chrono::steady_clock::now();
  const IcpResult r = icp_point_to_plane(source, target, tree, Eigen::Isometry3d::Identity(), o);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("ICP 6250 -> 5000 points: %.1f ms, %d iterations, rmse %.3g mm, inliers %.2f\n", ms,
              r.iterations, r.rmse * 1e3, r.inlier_fraction);
  const Eigen::Isometry3d err = truth.inverse() * r.transform;
  EXPECT_TRUE(r.converged);
  EXPECT_LT(err.translation().norm(), 0.001);
  EXPECT_LT(angle_deg(err.linear()), 0.1);
  EXPECT_EQ(r.degenerate_directions, 0);
  EXPECT_GT(r.normalized_eigenvalues(0), 0.01);
  std::printf("error %.3g mm, %.3g deg\n", err.translation().norm() * 1e3, angle_deg(err.linear()));
  EXPECT_GT(r.inlier_fraction, 0.75);  // the outliers near the box pair up too
  // rmse counts every pair, so the outliers within 5 cm dominate it; a tight
  // second pass (the usual refinement) pairs only the surface.
  IcpOptions tight = o;
  tight.max_correspondence = 0.01;  // the samples are ~5 mm apart
  const IcpResult r2 = icp_point_to_plane(source, target, tree, r.transform, tight);
  EXPECT_TRUE(r2.converged);
  std::printf("refined: rmse %.3g mm, inliers %.2f\n", r2.rmse * 1e3, r2.inlier_fraction);
  EXPECT_LT(r2.rmse, 0.0015);
  EXPECT_GT(r2.inlier_fraction, 0.75);
  EXPECT_LT((truth.inverse() * r2.transform).translation().norm(), 0.001);
  for (int k = 0; k < 5; ++k) EXPECT_LE(r.hessian_eigenvalues(k), r.hessian_eigenvalues(k + 1));

  // Every loss gets there, and subsampling too.
  for (RobustLoss loss : {RobustLoss::Huber, RobustLoss::Cauchy}) {
    IcpOptions lo = o;
    lo.loss = loss;
    lo.subsample = 2000;
    lo.max_iterations = 60;
    const IcpResult rl = icp_point_to_plane(source, target, tree, Eigen::Isometry3d::Identity(), lo);
    const Eigen::Isometry3d el = truth.inverse() * rl.transform;
    EXPECT_LT(el.translation().norm(), 0.002) << static_cast<int>(loss);
    EXPECT_LT(angle_deg(el.linear()), 0.2) << static_cast<int>(loss);
  }
}

TEST(PipelineCloud, IcpLeavesUnconstrainedCylinderDirectionsAlone) {
  std::mt19937 rng(3);
  const Cloud target = sample_cylinder(0.04, 0.1, 4000, rng);
  Cloud source = sample_cylinder(0.04, 0.1, 4000, rng);
  add_noise(&source, 0.0003, rng);
  source.normals.clear();
  // Move the cylinder sideways 5 mm (observable); the axis itself carries
  // no information about a turn about it or a slide along it.
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.translation() = Eigen::Vector3d(0.004, -0.003, 0);
  transform_cloud(truth.inverse(), &source);
  // Place the cylinder away from the origin, as a camera would see it.
  Eigen::Isometry3d place = Eigen::Isometry3d::Identity();
  place.translation() = Eigen::Vector3d(0.1, 0.2, 0.8);
  Cloud tgt = target, src = source;
  transform_cloud(place, &tgt);
  transform_cloud(place, &src);
  KdTree tree(tgt.points);
  const IcpResult r = icp_point_to_plane(src, tgt, tree, Eigen::Isometry3d::Identity(), IcpOptions{});
  const Eigen::Isometry3d found = place.inverse() * r.transform * place;  // in the cylinder's frame
  EXPECT_LT((found.translation().head<2>() - truth.translation().head<2>()).norm(), 0.0005);
  EXPECT_LT(std::abs(found.translation().z()), 0.001);  // did not slide along the axis
  EXPECT_LT(angle_deg(found.linear()), 0.5);            // did not spin about it
  EXPECT_EQ(r.degenerate_directions, 2);
  EXPECT_LT(r.normalized_eigenvalues(1), 1e-3);
  EXPECT_GT(r.normalized_eigenvalues(2), 1e-2);
  EXPECT_LT(r.hessian_eigenvalues(0), 1e-6 * r.hessian_eigenvalues(5));
}

TEST(PipelineCloud, IcpRefusesBadInput) {
  std::mt19937 rng(1);
  Cloud target = sample_box(Eigen::Vector3d(0.1, 0.1, 0.1), 500, rng);
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  start.translation() = Eigen::Vector3d(1, 2, 3);
  Cloud no_normals = target;
  no_normals.normals.clear();
  KdTree tree(target.points);
  IcpResult r = icp_point_to_plane(target, no_normals, tree, start, {});
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(r.transform.isApprox(start));
  r = icp_point_to_plane(Cloud{}, target, tree, start, {});
  EXPECT_FALSE(r.converged);
  Cloud nan_source;
  nan_source.points.assign(10, Eigen::Vector3d(kNaN, kNaN, kNaN));
  r = icp_point_to_plane(nan_source, target, tree, start, {});
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.correspondences, 0u);
}

// ---- filters.h

TEST(PipelineCloud, VoxelDownsampleAveragesPerVoxel) {
  Cloud c;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 10; ++k) {
        c.points.emplace_back((i + 0.5) * 0.01, (j + 0.5) * 0.01, (k + 0.5) * 0.01);
        c.normals.emplace_back(0, 0, 1);
      }
  c.points.emplace_back(kNaN, 0, 0);
  c.normals.emplace_back(0, 0, 1);
  const Cloud d = voxel_downsample(c, 0.02);
  ASSERT_EQ(d.size(), 125u);
  ASSERT_TRUE(d.has_normals());
  EXPECT_LT((d.points[0] - Eigen::Vector3d(0.01, 0.01, 0.01)).norm(), 1e-12);  // mean of 0.005, 0.015
  EXPECT_LT((d.normals[0] - Eigen::Vector3d(0, 0, 1)).norm(), 1e-12);
  EXPECT_EQ(voxel_downsample(c, 0.0101).size(), 1000u);
  EXPECT_EQ(voxel_downsample(c, 1.0).size(), 1u);
  EXPECT_EQ(voxel_downsample(Cloud{}, 0.01).size(), 0u);
}

TEST(PipelineCloud, OutlierFiltersRemoveInjectedFarPoints) {
  std::mt19937 rng(11);
  Cloud c = sample_box(Eigen::Vector3d(0.1, 0.1, 0.1), 3000, rng);
  const size_t inliers = c.size();
  std::uniform_real_distribution<double> u(0.2, 0.5);
  for (int i = 0; i < 30; ++i) {
    c.points.emplace_back(u(rng), -u(rng), u(rng));
    c.normals.emplace_back(1, 0, 0);
  }
  const Cloud s = remove_statistical_outliers(c, 12, 2.0);
  EXPECT_TRUE(s.has_normals());
  for (const auto& p : s.points) EXPECT_LT(p.cwiseAbs().maxCoeff(), 0.051);
  EXPECT_GT(s.size(), inliers * 97 / 100);

  const Cloud r = remove_radius_outliers(c, 0.01, 3);
  for (const auto& p : r.points) EXPECT_LT(p.cwiseAbs().maxCoeff(), 0.051);
  EXPECT_GT(r.size(), inliers * 97 / 100);

  Cloud tiny;
  tiny.points = {{0, 0, 0}, {1, 1, 1}};
  EXPECT_EQ(remove_statistical_outliers(tiny, 12, 2.0).size(), 2u);  // too few to judge
  EXPECT_EQ(remove_radius_outliers(tiny, 0.1, 1).size(), 0u);
}

TEST(PipelineCloud, EstimatedNormalsFollowTheSurface) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0, 1);
  Cloud sphere;
  for (int i = 0; i < 3000; ++i) sphere.points.push_back(0.1 * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized());
  estimate_normals(&sphere, 10, nullptr);
  ASSERT_TRUE(sphere.has_normals());
  double worst = 0;
  for (size_t i = 0; i < sphere.size(); ++i)
    worst = std::max(worst, std::acos(std::min(1.0, sphere.normals[i].dot(sphere.points[i].normalized()))));
  EXPECT_LT(worst * 180 / kPi, 10);  // outward everywhere

  const Eigen::Vector3d eye(0, 0, 1);
  estimate_normals(&sphere, 10, &eye);
  for (size_t i = 0; i < sphere.size(); ++i)
    EXPECT_GE(sphere.normals[i].dot(eye - sphere.points[i]), 0);

  Cloud two;
  two.points = {{0, 0, 0}, {1, 0, 0}};
  estimate_normals(&two, 10, nullptr);
  EXPECT_FALSE(two.has_normals());
}

// ---- mesh.h

TEST(PipelineCloud, ConvexHullOfCubeIsTheCube) {
  std::mt19937 rng(9);
  const double side = 0.1;
  Cloud pts = sample_box(Eigen::Vector3d(side, side, side), 2000, rng);
  for (int i = 0; i < 8; ++i)
    pts.points.emplace_back((i & 1 ? 0.5 : -0.5) * side, (i & 2 ? 0.5 : -0.5) * side, (i & 4 ? 0.5 : -0.5) * side);
  std::uniform_real_distribution<double> inside(-0.04, 0.04);
  for (int i = 0; i < 500; ++i) pts.points.emplace_back(inside(rng), inside(rng), inside(rng));
  // Shift it: volume and orientation must not depend on where it is.
  for (auto& p : pts.points) p += Eigen::Vector3d(0.3, -0.2, 0.9);
  pts.points.emplace_back(kNaN, 0, 0);  // ignored

  TriMesh mesh;
  std::string error;
  ASSERT_TRUE(convex_hull(pts.points, &mesh, &error)) << error;
  EXPECT_NEAR(mesh_volume(mesh), 1e-3, 1e-5);
  EXPECT_NEAR(mesh_area(mesh), 0.06, 0.0006);
  const Eigen::Vector3d center(0.3, -0.2, 0.9);
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d& a = mesh.vertices[f[0]];
    const Eigen::Vector3d n = (mesh.vertices[f[1]] - a).cross(mesh.vertices[f[2]] - a);
    const Eigen::Vector3d mid = (a + mesh.vertices[f[1]] + mesh.vertices[f[2]]) / 3;
    EXPECT_GT(n.dot(mid - center), 0);  // counter-clockwise seen from outside
  }
  // A closed 2-manifold: V - E + F = 2 with E = 3F/2.
  EXPECT_EQ(static_cast<int>(mesh.vertices.size()) - static_cast<int>(mesh.faces.size()) / 2, 2);
}

TEST(PipelineCloud, ConvexHullRefusesDegenerateInput) {
  TriMesh mesh;
  std::string error;
  EXPECT_FALSE(convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, &mesh, &error));
  EXPECT_NE(error.find("at least 4"), std::string::npos) << error;
  std::vector<Eigen::Vector3d> flat;
  for (int i = 0; i < 50; ++i) flat.emplace_back(i % 7, i / 7, 0);
  error.clear();
  EXPECT_FALSE(convex_hull(flat, &mesh, &error));
  EXPECT_FALSE(error.empty());
  EXPECT_TRUE(mesh.faces.empty());
  EXPECT_FALSE(convex_hull(std::vector<Eigen::Vector3d>(10, Eigen::Vector3d(kNaN, 0, 0)), &mesh, &error));
}

TEST(PipelineCloud, WriteObjWritesWholeFileOrNothing) {
  TriMesh tet;
  tet.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tet.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_NEAR(mesh_volume(tet), 1.0 / 6, 1e-12);
  const std::string path = ::testing::TempDir() + "efc_cloud_tet.obj";
  std::string error;
  ASSERT_TRUE(write_obj(path, tet, &error)) << error;
  std::ifstream in(path);
  std::string line;
  int v = 0, f = 0;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0) ++v;
    if (line.rfind("f ", 0) == 0) ++f;
    if (f == 1 && line.rfind("f ", 0) == 0) {
      EXPECT_EQ(line, "f 1 3 2");  // 1-based
    }
  }
  EXPECT_EQ(v, 4);
  EXPECT_EQ(f, 4);
  std::remove(path.c_str());
  EXPECT_FALSE(write_obj("/nonexistent-dir/x.obj", tet, &error));
  EXPECT_FALSE(error.empty());
  TriMesh broken = tet;
  broken.faces.emplace_back(0, 1, 9);
  EXPECT_FALSE(write_obj(path, broken, &error));
  EXPECT_FALSE(std::ifstream(path).good());
}

// ---- fusion.h

TEST(PipelineCloud, FusionKeepsTheSurfaceAndDropsTransients) {
  std::mt19937 rng(21);
  const Eigen::Vector3d size(0.12, 0.08, 0.05);
  FusionOptions o;
  o.min_observations = 3;
  PartFusion fusion(o);
  std::uniform_real_distribution<double> where(-0.2, 0.2);
  std::normal_distribution<double> blob(0, 0.01);
  for (int frame = 0; frame < 10; ++frame) {
    Cloud c = sample_box(size, 3000, rng);
    add_noise(&c, 0.0005, rng);
    // A transient: a hand-sized blob somewhere else each frame.
    const Eigen::Vector3d hand(where(rng), where(rng), 0.1 + where(rng));
    for (int i = 0; i < 300; ++i) {
      c.points.push_back(hand + Eigen::Vector3d(blob(rng), blob(rng), blob(rng)));
      c.normals.emplace_back(0, 0, 1);
    }
    fusion.add_frame(c);
  }
  EXPECT_EQ(fusion.frames(), 10);
  const Cloud f = fusion.fused();
  ASSERT_TRUE(f.has_normals());
  ASSERT_GT(f.size(), 1000u);
  size_t off_surface = 0;
  for (const auto& p : f.points) {
    const Eigen::Vector3d q = p.cwiseAbs() - size / 2;  // <= 0 inside, one coordinate ~0 on the surface
    if (q.maxCoeff() > 0.003 || q.maxCoeff() < -0.003) ++off_surface;
  }
  EXPECT_EQ(off_surface, 0u);

  TriMesh mesh;
  std::string error, note;
  ASSERT_TRUE(closed_mesh(f, &mesh, &error, &note)) << error;
  EXPECT_NEAR(mesh_volume(mesh), size.prod(), 0.05 * size.prod()) << note;
  EXPECT_NE(note.find("convex hull of"), std::string::npos);
}

TEST(PipelineCloud, TheMasksVoteDropsWhatAMaskDrawnTooWideTookIn) {
  // A knob-like box in 12 frames. In every third its mask was drawn too
  // wide and took in a strip of the face behind it (2 cm back, 1 cm out);
  // in the others that strip lay just outside the mask, in its outline. In
  // every third but one the mask was drawn too narrow and left the box's
  // top rim (its last 3 mm) in the outline instead.
  std::mt19937 rng(5);
  const Eigen::Vector3d size(0.06, 0.06, 0.02);
  auto strip = [&]() {
    Cloud c;
    for (double x = -0.04; x <= 0.04; x += 0.001)
      for (double y = 0.03; y <= 0.04; y += 0.001) c.points.emplace_back(x, y, -0.03), c.normals.emplace_back(0, 0, 1);
    return c;
  };
  auto split_rim = [&](const Cloud& box, Cloud* inside, Cloud* rim) {
    for (size_t i = 0; i < box.size(); ++i) {
      Cloud& to = box.points[i].y() > size.y() / 2 - 0.003 ? *rim : *inside;
      to.points.push_back(box.points[i]);
      to.normals.push_back(box.normals[i]);
    }
  };
  PartFusion part(FusionOptions{}), outline(FusionOptions{});
  for (int frame = 0; frame < 12; ++frame) {
    Cloud seen = sample_box(size, 4000, rng), out;
    if (frame % 3 == 0) {
      seen = concatenate(seen, strip());
    } else {
      out = strip();
      if (frame % 3 == 1) {
        Cloud inside;
        split_rim(seen, &inside, &out);
        seen = inside;
      }
    }
    part.add_frame(seen);
    outline.add_frame(out);
  }
  auto behind = [](const Cloud& c) {
    int n = 0;
    for (const Eigen::Vector3d& p : c.points) n += p.z() < -0.02;
    return n;
  };
  auto rim = [&](const Cloud& c) {
    int n = 0;
    for (const Eigen::Vector3d& p : c.points) n += p.y() > size.y() / 2 - 0.003 && p.z() > -0.011;
    return n;
  };
  const Cloud plain = part.fused();
  EXPECT_GT(behind(plain), 50);  // four frames agree on the strip: the fusion alone keeps it
  int dropped = -1;
  const Cloud voted = part.fused(&outline, &dropped);
  EXPECT_EQ(behind(voted), 0);
  EXPECT_GT(dropped, 100);
  EXPECT_GT(rim(voted), rim(plain) * 9 / 10);  // the rim, inside in eight frames of twelve, stays
  // An empty outline drops nothing.
  const PartFusion nothing_outside(FusionOptions{});
  EXPECT_EQ(part.fused(&nothing_outside, &dropped).size(), plain.size());
  EXPECT_EQ(dropped, 0);
  EXPECT_EQ(outline.observations_at(Eigen::Vector3d(0, 0.035, -0.03)), 8);
  EXPECT_EQ(outline.observations_at(Eigen::Vector3d(1, 1, 1)), 0);
}

TEST(PipelineCloud, FusionOfOneFrameKeepsEverything) {
  std::mt19937 rng(2);
  PartFusion fusion(FusionOptions{});
  Cloud c = sample_box(Eigen::Vector3d(0.1, 0.1, 0.1), 2000, rng);
  fusion.add_frame(c);
  EXPECT_EQ(fusion.required_observations(), 1);
  const Cloud f = fusion.fused();
  EXPECT_GT(f.size(), voxel_downsample(c, 0.003).size() * 95 / 100);  // only the outlier filter acts
  // A second frame in a different place: now each voxel needs both.
  Cloud moved = c;
  for (auto& p : moved.points) p.x() += 1.0;
  fusion.add_frame(moved);
  EXPECT_EQ(fusion.fused().size(), 0u);
  PartFusion none(FusionOptions{});
  EXPECT_EQ(none.fused().size(), 0u);
  none.add_frame(Cloud{});
  EXPECT_EQ(none.frames(), 1);
}

TEST(PipelineCloud, ClosedMeshDropsIsolatedPointsAndRefusesFlatClouds) {
  std::mt19937 rng(8);
  Cloud c = sample_box(Eigen::Vector3d(0.1, 0.1, 0.1), 3000, rng);
  c.points.emplace_back(0.5, 0.5, 0.5);  // one stray point would double the hull's volume
  TriMesh mesh;
  std::string error, note;
  ASSERT_TRUE(closed_mesh(c, &mesh, &error, &note)) << error;
  EXPECT_NEAR(mesh_volume(mesh), 1e-3, 5e-5) << note;
  EXPECT_NE(note.find("(1 isolated"), std::string::npos) << note;
  ASSERT_TRUE(closed_mesh(c, &mesh, &error));

  Cloud flat;
  for (int i = 0; i < 200; ++i) flat.points.emplace_back(0.001 * (i % 20), 0.001 * (i / 20), 0);
  EXPECT_FALSE(closed_mesh(flat, &mesh, &error));
  EXPECT_FALSE(error.empty());
  EXPECT_FALSE(closed_mesh(Cloud{}, &mesh, &error));
}

}  // namespace
}  // namespace efc::pipeline
