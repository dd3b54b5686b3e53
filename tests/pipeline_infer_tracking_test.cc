// The part tracker (pipeline/infer/part_tracking.h) on made-up clouds: a
// round part that stops showing its turn does not go on turning when the
// tracker carries on only the motion it saw (the grip's tracking), and
// does when it carries on every step (the parts' own).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pipeline/infer/part_tracking.h"

namespace {

using namespace efc::pipeline;
using Eigen::Vector3d;
constexpr double kPi = 3.14159265358979323846;

// A ring (radius 3 cm, 2 cm tall, axis z) with outward normals, and
// optionally a ridge on its side: a box 1 cm out, 6 mm wide, turned by
// `angle` about z. Without the ridge a turn about z does not show at all.
Cloud knob(bool ridge, double angle) {
  Cloud c;
  for (int i = 0; i < 90; ++i)
    for (int k = 0; k < 6; ++k) {
      const double a = 2 * kPi * i / 90;
      c.points.push_back(Vector3d(0.03 * std::cos(a), 0.03 * std::sin(a), 0.02 * k / 5));
      c.normals.push_back(Vector3d(std::cos(a), std::sin(a), 0));
    }
  if (ridge) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, Vector3d::UnitZ()).toRotationMatrix();
    for (int i = 0; i <= 10; ++i)
      for (int k = 0; k < 6; ++k) {
        const double z = 0.02 * k / 5, r = 0.03 + 0.001 * i;
        for (int side : {-1, 1}) {
          c.points.push_back(R * Vector3d(r, side * 0.003, z));
          c.normals.push_back(R * Vector3d(0, side, 0));
        }
      }
    // More points in the ridged frames: the tracker models the part on the
    // frame that shows most of it (frame 0).
    for (int i = 0; i < 90; ++i) {
      const double a = 2 * kPi * (i + 0.5) / 90;
      c.points.push_back(Vector3d(0.03 * std::cos(a), 0.03 * std::sin(a), 0.01));
      c.normals.push_back(Vector3d(std::cos(a), std::sin(a), 0));
    }
  }
  return c;
}

TEST(PipelineInferTracking, ARoundPartThatStopsShowingItsTurnStopsTurning) {
  // Frames 0 to 2 show the ridge turning 0.1 rad a frame; from frame 3 on
  // the ridge is hidden and the part holds still. A tracker that starts
  // each frame from the last step carried on would keep turning the part
  // 0.1 rad a frame, since nothing in the plain ring stops it.
  const int frames = 30;
  std::vector<Cloud> clouds;
  for (int f = 0; f < frames; ++f) clouds.push_back(f < 3 ? knob(true, 0.1 * f) : knob(false, 0));
  const std::vector<Eigen::Isometry3d> to_object(frames, Eigen::Isometry3d::Identity());
  TrackOptions seen_only;
  seen_only.carry_unseen_motion = false;
  const PartTrack t = track_clouds(clouds, to_object, seen_only);
  ASSERT_EQ(t.reference_frame, 0);
  ASSERT_TRUE(t.tracked[2]);
  EXPECT_NEAR(Eigen::AngleAxisd(t.motion[2].linear()).angle(), 0.2, 0.02);
  for (int f = 3; f < frames; ++f) {
    ASSERT_TRUE(t.tracked[f]) << f;
    EXPECT_LT(Eigen::AngleAxisd(t.motion[f].linear()).angle(), 0.35) << f;
    EXPECT_LT(t.motion[f].translation().norm(), 0.003) << f;
  }
  // Carrying every step on, the turn runs on by 0.1 rad a frame.
  const PartTrack carried = track_clouds(clouds, to_object);
  ASSERT_TRUE(carried.tracked[10]);
  EXPECT_NEAR(Eigen::AngleAxisd(carried.motion[10].linear()).angle(), 1.0, 0.05);
}

}  // namespace
