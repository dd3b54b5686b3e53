// The information a part's registration gives each sample of its track
// (part_samples(), from the ICP's Hessian): a real point-to-plane ICP on a
// round knob turned and moved away from its reference pose, then the
// sample's information matrix read in the object frame. The knob's spin
// about its own axis must cost nothing; its tilt and its slide along the
// axis must cost much. A wrong transform of the Hessian (the frame, the
// sign, the centre) puts the free direction elsewhere.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <cmath>

#include "pipeline/cloud/icp.h"
#include "pipeline/cloud/kdtree.h"
#include "pipeline/infer/joint_estimate.h"

namespace efc::pipeline {
namespace {

using Eigen::Vector3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;

constexpr double kPi = 3.14159265358979323846;

// A closed cylinder (side and both caps) about `axis` through `centre`, with
// outward normals.
Cloud cylinder(const Vector3d& centre, const Vector3d& axis, double radius, double length) {
  Cloud c;
  const Vector3d a = axis.normalized(), e1 = a.unitOrthogonal(), e2 = a.cross(e1);
  for (int i = 0; i < 48; ++i) {
    const double phi = 2 * kPi * i / 48;
    const Vector3d radial = std::cos(phi) * e1 + std::sin(phi) * e2;
    for (int k = 0; k <= 6; ++k) {
      c.points.push_back(centre + radial * radius + a * length * (k / 6.0 - 0.5));
      c.normals.push_back(radial);
    }
    for (int k = 1; k <= 4; ++k)
      for (int side : {-1, 1}) {
        c.points.push_back(centre + radial * radius * k / 4.0 + side * a * length / 2);
        c.normals.push_back(side * a);
      }
  }
  return c;
}

TEST(PipelineInferInformation, AKnobsSpinIsFreeAndItsSlideIsNot) {
  const Vector3d centre(0.2, -0.3, 0.7), axis = Vector3d(0.3, -1, 0.1).normalized();
  const Cloud model = cylinder(centre, axis, 0.02, 0.02);
  // The frame: the knob tilted 25 degrees and moved 3 cm.
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() = Eigen::AngleAxisd(25 * kPi / 180, Vector3d(1, 0.4, 0.2).normalized()).toRotationMatrix();
  motion.translation() = Vector3d(0.03, 0.01, -0.02) + centre - motion.linear() * centre;
  Cloud frame = model;
  transform_cloud(motion, &frame);
  const KdTree tree(model.points);
  IcpOptions options;
  const IcpResult r = icp_point_to_plane(frame, model, tree, motion.inverse(), options);
  ASSERT_TRUE(r.converged);

  PartTrack track;
  track.reference_frame = 0;
  track.model = model;
  track.motion = {r.transform.inverse()};
  track.tracked = {true};
  track.rmse = {r.rmse};
  track.inliers = {r.inlier_fraction};
  track.conditioning = {r.normalized_eigenvalues(0)};
  track.hessian = {r.hessian};
  track.hessian_center = {r.hessian_center};
  std::vector<std::vector<int>> frames;
  const Track samples = part_samples(track, centroid(model), 1, &frames);
  ASSERT_TRUE(samples.has_information());
  const Eigen::Matrix<double, 6, 6>& W = samples.information[0];

  // Directions in the object frame, at the frame's pose: the knob's axis is
  // motion.linear() * axis, through the moved centroid.
  const Vector3d moved_axis = motion.linear() * axis;
  auto cost = [&](const Vector3d& rotation, const Vector3d& translation) {
    Vec6 d;
    d << rotation, translation;
    return d.dot(W * d) / d.squaredNorm();
  };
  const double spin = cost(moved_axis, Vector3d::Zero());
  const double tilt = cost(moved_axis.unitOrthogonal(), Vector3d::Zero());
  const double slide = cost(Vector3d::Zero(), moved_axis);
  const double sideways = cost(Vector3d::Zero(), moved_axis.unitOrthogonal());
  EXPECT_LT(spin, 1e-6 * slide) << "spin " << spin << " slide " << slide;
  EXPECT_GT(tilt, 0.1 * slide * 0.02 * 0.02) << "tilt " << tilt;
  EXPECT_GT(sideways, 0.1 * slide) << "sideways " << sideways;
  // The spin about the axis through a point off it is not free: it moves
  // the centroid.
  const Vector3d lever = 0.02 * moved_axis.unitOrthogonal();
  EXPECT_GT(cost(moved_axis, -moved_axis.cross(lever)), 1e3 * spin);

  // The track of a point 5 cm off the knob (the pose of any point of the
  // part will do): the same spin now moves that point about the axis, and
  // only that combination is free.
  const Vector3d off = centroid(model) + Vector3d(0.05, 0, 0.02);
  const Track off_samples = part_samples(track, off, 1, &frames);
  const Eigen::Matrix<double, 6, 6>& W_off = off_samples.information[0];
  const Vector3d point = motion * off, knob = motion * centroid(model);
  Vec6 turn, pure;
  turn << moved_axis, moved_axis.cross(point - knob);
  pure << moved_axis, Vector3d::Zero();
  EXPECT_LT(turn.dot(W_off * turn), 1e-6 * slide * turn.squaredNorm());
  EXPECT_GT(pure.dot(W_off * pure), 1e3 * turn.dot(W_off * turn));
}

// A knob with a small pointer ridge: its spin is nearly free (the ridge's
// few points hold it), below the tracker's threshold, so the tracker never
// moves along it and the pose there is only the registration's start.
// drop_unconstrained gives the spin no information at all; the slide keeps
// all of its own.
TEST(PipelineInferInformation, TheSpinTheTrackerLeftAloneGetsNoInformation) {
  const Vector3d centre(0.1, 0.2, 0.5), axis(0, -1, 0);
  Cloud model = cylinder(centre, axis, 0.025, 0.02);
  // The ridge: a 4 mm x 2 mm x 12 mm bar on the front cap, off the axis.
  const Vector3d front = centre + axis * 0.01;
  for (int i = 0; i < 6; ++i)
    for (int side : {-1, 1}) {
      model.points.push_back(front + axis * 0.002 + Vector3d(side * 0.002, 0, 0.004 + 0.002 * i));
      model.normals.push_back(Vector3d(side, 0, 0));
    }
  Cloud frame = model;
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.translation() = Vector3d(0.004, -0.003, 0.002);
  transform_cloud(motion, &frame);
  const KdTree tree(model.points);
  IcpOptions options;
  options.degenerate_threshold = kTrackDegenerateThreshold;
  const IcpResult r = icp_point_to_plane(frame, model, tree, motion.inverse(), options);
  ASSERT_TRUE(r.converged);
  // The premise: the spin is held, but only weakly.
  ASSERT_GT(r.normalized_eigenvalues(0), 1e-5);
  ASSERT_LT(r.normalized_eigenvalues(0), kTrackDegenerateThreshold);
  ASSERT_GE(r.normalized_eigenvalues(1), kTrackDegenerateThreshold);

  PartTrack track;
  track.reference_frame = 0;
  track.model = model;
  track.motion = {r.transform.inverse()};
  track.tracked = {true};
  track.rmse = {std::max(r.rmse, 1e-4)};
  track.inliers = {r.inlier_fraction};
  track.conditioning = {r.normalized_eigenvalues(0)};
  track.hessian = {r.hessian};
  track.hessian_center = {r.hessian_center};
  track.hessian_scale = {r.scale_length};
  std::vector<std::vector<int>> frames;
  const Eigen::Matrix<double, 6, 6> kept = part_samples(track, centroid(model), 1, &frames, false).information[0];
  const Eigen::Matrix<double, 6, 6> dropped = part_samples(track, centroid(model), 1, &frames, true).information[0];
  // Dropping takes one direction away: the knob's spin (its rotation part
  // along the axis), which the ridge held a little.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(dropped);
  const Vec6 free = eig.eigenvectors().col(0);
  EXPECT_GT(std::abs(free.head<3>().normalized().dot(axis)), 0.99);
  EXPECT_LT(free.dot(dropped * free), 1e-9 * eig.eigenvalues()(1));
  EXPECT_GT(free.dot(kept * free), 1e3 * std::max(free.dot(dropped * free), 1e-12));
  Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> removed(kept - dropped);
  removed.setThreshold(1e-9);
  EXPECT_EQ(removed.rank(), 1);
  Vec6 slide;
  slide << Vector3d::Zero(), axis;
  EXPECT_NEAR(slide.dot(dropped * slide), slide.dot(kept * slide), 1e-6 * slide.dot(kept * slide));
}

}  // namespace
}  // namespace efc::pipeline
