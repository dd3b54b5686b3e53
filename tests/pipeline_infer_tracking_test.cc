// The part tracker (pipeline/infer/part_tracking.h) on made-up clouds: a
// round part that stops showing its turn does not go on turning when the
// tracker carries on only the motion it saw (the grip's tracking), and
// does when it carries on every step (the parts' own); a lid snapped open
// and a drawer snapped out, held there for a while, are found again.
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

// A box 30 x 20 x 2 cm seen on its top (or its underside), front and
// sides (outward normals), moved by `pose`.
Cloud box_surface(const Eigen::Isometry3d& pose, bool underside = false) {
  Cloud c;
  auto add = [&](const Vector3d& p, const Vector3d& n) {
    c.points.push_back(pose * p);
    c.normals.push_back(pose.linear() * n);
  };
  const double face_z = underside ? -0.01 : 0.01;
  for (int i = 0; i <= 30; ++i)
    for (int j = 0; j <= 20; ++j)
      add(Vector3d(-0.15 + 0.01 * i, -0.1 + 0.01 * j, face_z), Vector3d(0, 0, underside ? -1 : 1));
  for (int i = 0; i <= 30; ++i)
    for (int k = 0; k <= 4; ++k) add(Vector3d(-0.15 + 0.01 * i, -0.1, -0.01 + 0.005 * k), -Vector3d::UnitY());
  for (int side : {-1, 1})
    for (int j = 0; j <= 20; ++j)
      for (int k = 0; k <= 4; ++k)
        add(Vector3d(side * 0.15, -0.1 + 0.01 * j, -0.01 + 0.005 * k), side * Vector3d::UnitX());
  return c;
}

// Frames 10 to 19 hold the part at `moved` (reached in one frame, out of
// ICP's reach from the frame before); the others at rest.
// `underside`: the moved part shows its other face (a lid lifted towards
// the person in front).
std::vector<Cloud> snapped(const Eigen::Isometry3d& moved, bool underside = false) {
  std::vector<Cloud> clouds;
  for (int f = 0; f < 30; ++f) {
    const bool away = f >= 10 && f < 20;
    clouds.push_back(box_surface(away ? moved : Eigen::Isometry3d::Identity(), away && underside));
  }
  return clouds;
}

TEST(PipelineInferTracking, ALidSnappedOpenIsFoundAgain) {
  // 60 degrees about its back edge (x through y = 0.1, z = 0).
  Eigen::Isometry3d open = Eigen::Isometry3d::Identity();
  open.linear() = Eigen::AngleAxisd(kPi / 3, Vector3d::UnitX()).toRotationMatrix();
  open.translation() = Vector3d(0, 0.1, 0) - open.linear() * Vector3d(0, 0.1, 0);
  const std::vector<Eigen::Isometry3d> to_object(30, Eigen::Isometry3d::Identity());
  // Showing the same faces open, and showing its inside: a model of its top
  // alone fits the inside only flipped over, so the search has the unseen
  // face too.
  for (bool underside : {false, true}) {
    const PartTrack t = track_clouds(snapped(open, underside), to_object);
    ASSERT_EQ(t.reference_frame, 0);
    for (int f = 0; f < 30; ++f) {
      ASSERT_TRUE(t.tracked[f]) << f << (underside ? " (underside)" : "");
      const Eigen::Isometry3d want = f >= 10 && f < 20 ? open : Eigen::Isometry3d::Identity();
      EXPECT_LT(Eigen::AngleAxisd(t.motion[f].linear() * want.linear().transpose()).angle(), 0.03) << f << underside;
      EXPECT_LT((t.motion[f] * Vector3d(0, -0.1, 0) - want * Vector3d(0, -0.1, 0)).norm(), 0.02) << f << underside;
    }
  }
  // Without the search (the grip's tracking), the open frames stay lost.
  TrackOptions no_search;
  no_search.reacquire_leaps = false;
  const PartTrack lost = track_clouds(snapped(open), to_object, no_search);
  for (int f = 10; f < 20; ++f) EXPECT_FALSE(lost.tracked[f]) << f;
}

TEST(PipelineInferTracking, WithinAGraspTheChainDoesNotRestartFromTheReference) {
  // The box tilts 0.04 rad a frame about x to 0.8 rad (frames 0 to 20),
  // then shows its rest pose again in frame 21 (out of ICP's reach from
  // where the chain is), is unseen for five frames, and shows its rest
  // pose again from frame 27. A part's tracker may start any frame from
  // the reference pose and so finds frame 21 at rest. The grip's does not:
  // a hand that leaps back within a grasp is not the hand it held (a
  // hand's palm looks much alike a quarter turn on, where a reference
  // start can win by a few points); after a gap it is a new grasp and may.
  const int frames = 33;
  std::vector<Cloud> clouds;
  for (int f = 0; f < frames; ++f) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    if (f <= 20) pose.linear() = Eigen::AngleAxisd(0.04 * f, Vector3d::UnitX()).toRotationMatrix();
    clouds.push_back(f >= 22 && f < 27 ? Cloud() : box_surface(pose));
  }
  const std::vector<Eigen::Isometry3d> to_object(frames, Eigen::Isometry3d::Identity());
  TrackOptions part;
  part.reacquire_leaps = false;
  TrackOptions grip = part;
  grip.restart_from_reference = false;
  const PartTrack restarted = track_clouds(clouds, to_object, part), held = track_clouds(clouds, to_object, grip);
  for (const PartTrack* t : {&restarted, &held}) {
    ASSERT_EQ(t->reference_frame, 0);
    ASSERT_TRUE(t->tracked[20]);
    EXPECT_NEAR(Eigen::AngleAxisd(t->motion[20].linear()).angle(), 0.8, 0.02);
    for (int f = 27; f < frames; ++f) {
      ASSERT_TRUE(t->tracked[f]) << f;
      EXPECT_LT(Eigen::AngleAxisd(t->motion[f].linear()).angle(), 0.02) << f;
    }
  }
  ASSERT_TRUE(restarted.tracked[21]);
  EXPECT_LT(Eigen::AngleAxisd(restarted.motion[21].linear()).angle(), 0.02);
  EXPECT_FALSE(held.tracked[21] && Eigen::AngleAxisd(held.motion[21].linear()).angle() < 0.1);
}

TEST(PipelineInferTracking, ADrawerSnappedOutIsFoundAgainAsASlide) {
  // 30 cm out along -y in one frame, clear of where it was: found again as
  // that slide, not as a turn.
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.translation() = Vector3d(0, -0.3, 0);
  const std::vector<Eigen::Isometry3d> to_object(30, Eigen::Isometry3d::Identity());
  const PartTrack t = track_clouds(snapped(out), to_object);
  for (int f = 10; f < 20; ++f) {
    ASSERT_TRUE(t.tracked[f]) << f;
    EXPECT_LT(Eigen::AngleAxisd(t.motion[f].linear()).angle(), 0.02) << f;
    EXPECT_LT((t.motion[f].translation() - out.translation()).norm(), 0.003) << f;
  }
}

}  // namespace
