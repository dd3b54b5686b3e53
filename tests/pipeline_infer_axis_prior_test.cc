// The body's axes (pipeline/infer/body_frame.h) and the prior they put on
// the joints' axes (pipeline/infer/axis_prior.h): a cabinet turned on the
// floor, seen from a corner, and a drum, which has no horizontal axes.
#include <gtest/gtest.h>

#include <cmath>

#include "pipeline/infer/axis_prior.h"
#include "pipeline/infer/body_frame.h"

namespace {

using namespace efc::pipeline;
using Eigen::Vector3d;

constexpr double kDegree = 3.14159265358979323846 / 180;

// A cabinet 0.8 x 0.5 x 0.7 m turned `yaw` about up: its front, its right
// side and its top, points 1 cm apart, each normal tilted by up to
// `noise_degrees` as a fused depth's are.
Cloud cabinet(double yaw, double noise_degrees) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(yaw, Vector3d::UnitZ()).toRotationMatrix();
  Cloud c;
  unsigned state = 12345u;
  auto jitter = [&]() {
    state = state * 1664525u + 1013904223u;
    return noise_degrees * kDegree * (2.0 * (state >> 8) / double(1u << 24) - 1.0);
  };
  auto add = [&](const Vector3d& p, const Vector3d& n) {
    const Vector3d tilted = (Eigen::AngleAxisd(jitter(), Vector3d::UnitX()) *
                             Eigen::AngleAxisd(jitter(), Vector3d::UnitY()) * n);
    c.points.push_back(turn * p);
    c.normals.push_back(turn * tilted);
  };
  for (double a = -0.4; a <= 0.4; a += 0.01)
    for (double z = 0; z <= 0.7; z += 0.01) add({a, -0.25, z}, {0, -1, 0});  // front
  for (double b = -0.25; b <= 0.25; b += 0.01)
    for (double z = 0; z <= 0.7; z += 0.01) add({0.4, b, z}, {1, 0, 0});  // right side
  for (double a = -0.4; a <= 0.4; a += 0.01)
    for (double b = -0.25; b <= 0.25; b += 0.01) add({a, b, 0.7}, {0, 0, 1});  // top
  return c;
}

JointEstimate joint(const std::string& type, const Vector3d& axis, const Vector3d& origin = Vector3d(0.4, -0.25, 0.3)) {
  JointEstimate j;
  j.type = type;
  j.axis = axis.normalized();
  j.origin = origin;
  return j;
}

// `axis` turned by `degrees` about `about`.
Vector3d tilted(const Vector3d& axis, const Vector3d& about, double degrees) {
  return Eigen::AngleAxisd(degrees * kDegree, about.normalized()) * axis;
}

TEST(PipelineInferAxisPrior, ASquareBodysAxesAreFoundFromItsFacesUnderTheirNoise) {
  const double yaw = 0.3;
  const BodyFrame frame = body_frame(cabinet(yaw, 10));
  ASSERT_TRUE(frame.found);
  EXPECT_NEAR(frame.yaw, yaw, 0.5 * kDegree);
  EXPECT_GT(frame.box_share, 0.95);
  EXPECT_NEAR(frame.u.dot(Vector3d(std::cos(yaw), std::sin(yaw), 0)), 1.0, 1e-4);
  EXPECT_NEAR(frame.v.dot(Vector3d(-std::sin(yaw), std::cos(yaw), 0)), 1.0, 1e-4);

  // A drum: every upright normal a different azimuth, no horizontal axes.
  Cloud drum;
  for (double t = 0; t < 6.283; t += 0.02)
    for (double z = 0; z <= 0.7; z += 0.01) {
      drum.points.emplace_back(0.3 * std::cos(t), 0.3 * std::sin(t), z);
      drum.normals.emplace_back(std::cos(t), std::sin(t), 0);
    }
  EXPECT_FALSE(body_frame(drum).found);
  EXPECT_FALSE(body_frame(Cloud{}).found);  // no normals
}

TEST(PipelineInferAxisPrior, AJointReadAFewDegreesOffTheBodysAxisIsTakenOntoIt) {
  const double yaw = 0.3;
  const BodyFrame frame = body_frame(cabinet(yaw, 10));
  ASSERT_TRUE(frame.found);

  // A door's hinge read 8 degrees off upright: upright, through the same
  // point, turning the same way.
  JointEstimate door = joint("revolute", tilted(Vector3d::UnitZ(), Vector3d::UnitX(), 8));
  const Vector3d origin = door.origin;
  AxisPrior prior = apply_axis_prior(frame, &door);
  EXPECT_EQ(prior.axis, "up");
  EXPECT_NEAR(prior.angle, 8 * kDegree, 1e-9);
  EXPECT_NEAR(door.axis.dot(Vector3d::UnitZ()), 1.0, 1e-12);
  EXPECT_EQ(door.origin, origin);

  // A drawer read 12 degrees off the body's depth (v), in the sense out of
  // its front (-v): onto -v.
  JointEstimate drawer = joint("prismatic", tilted(-frame.v, Vector3d(0.3, 0.2, 1), 12));
  prior = apply_axis_prior(frame, &drawer);
  EXPECT_EQ(prior.axis, "v");
  EXPECT_NEAR(drawer.axis.dot(-frame.v), 1.0, 1e-12);

  // A knob on the side, spinning about u, read 15 degrees off: onto u.
  JointEstimate knob = joint("continuous", tilted(frame.u, Vector3d::UnitZ(), -15));
  prior = apply_axis_prior(frame, &knob);
  EXPECT_EQ(prior.axis, "u");
  EXPECT_NEAR(knob.axis.dot(frame.u), 1.0, 1e-12);

  // A lamp's arm on a slanted hinge, 35 degrees off every axis: kept.
  const Vector3d slanted = tilted(frame.u, frame.v, 35);
  JointEstimate arm = joint("revolute", slanted);
  prior = apply_axis_prior(frame, &arm);
  EXPECT_TRUE(prior.axis.empty());
  EXPECT_NEAR(prior.angle, 35 * kDegree, 1e-9);
  EXPECT_NEAR(arm.axis.dot(slanted), 1.0, 1e-12);

  // A fixed part has no axis to move.
  JointEstimate still = joint("fixed", tilted(Vector3d::UnitZ(), Vector3d::UnitX(), 5));
  const Vector3d kept = still.axis;
  EXPECT_TRUE(apply_axis_prior(frame, &still).axis.empty());
  EXPECT_EQ(still.axis, kept);
}

TEST(PipelineInferAxisPrior, APressReadFarOffEveryAxisPressesAlongTheBodysAxisItsFaceShows) {
  const BodyFrame frame = body_frame(cabinet(0.3, 10));
  ASSERT_TRUE(frame.found);
  // A round button on the cabinet's front: its face (normal -v, out of the
  // front) and its rim, a few hundred points.
  Cloud button;
  for (double x = -0.012; x <= 0.012; x += 0.002)
    for (double z = -0.012; z <= 0.012; z += 0.002)
      if (x * x + z * z <= 0.012 * 0.012) {
        button.points.push_back(Vector3d(x, -0.005, z));
        button.normals.push_back(-frame.v);
      }
  for (double t = 0; t < 6.283; t += 0.1)
    for (double y = -0.005; y <= 0; y += 0.0025) {
      button.points.emplace_back(0.012 * std::cos(t), y, 0.012 * std::sin(t));
      button.normals.push_back(std::cos(t) * frame.u + std::sin(t) * frame.up);
    }
  // Pressed 4 mm in (+v), read 40 degrees off towards u and 10 up (a
  // finger's wander across the face).
  const Vector3d read = tilted(tilted(frame.v, frame.up, 40), frame.u, 10);
  JointEstimate press = joint("prismatic", read);
  press.range_hi = 0.004;
  AxisPrior prior = apply_axis_prior(frame, &press, &button);
  EXPECT_TRUE(prior.by_face);
  EXPECT_EQ(prior.axis, "v");
  EXPECT_NEAR(press.axis.dot(frame.v), 1.0, 1e-12);  // the estimate's sense: in
  // Without its shape, or slid further than a press goes (a slider's knob
  // slides across its face): kept.
  JointEstimate unseen = joint("prismatic", read);
  unseen.range_hi = 0.004;
  EXPECT_TRUE(apply_axis_prior(frame, &unseen).axis.empty());
  JointEstimate slider = joint("prismatic", read);
  slider.range_hi = 0.06;
  EXPECT_TRUE(apply_axis_prior(frame, &slider, &button).axis.empty());
  EXPECT_NEAR(slider.axis.dot(read), 1.0, 1e-12);
}

TEST(PipelineInferAxisPrior, APressOrAKnobNoTrackTypedGoesIntoTheBodysFaceItSitsOn) {
  const double yaw = 0.3;
  const Cloud body = cabinet(yaw, 10);
  const BodyFrame frame = body_frame(body);
  ASSERT_TRUE(frame.found);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(yaw, Vector3d::UnitZ()).toRotationMatrix();
  // A button 5 mm proud of the front (at y = -0.25 before the yaw), a third
  // of the way up; one on the top; one on the front's top edge, between two
  // faces.
  const Vector3d on_front = turn * Vector3d(0.1, -0.255, 0.25), on_top = turn * Vector3d(-0.1, 0.0, 0.705),
                 on_edge = turn * Vector3d(0.0, -0.25, 0.7);
  Vector3d into;
  ASSERT_TRUE(face_it_sits_on(frame, body, on_front, &into));
  EXPECT_NEAR(std::abs(into.dot(frame.v)), 1.0, 1e-12);
  ASSERT_TRUE(face_it_sits_on(frame, body, on_top, &into));
  EXPECT_NEAR(std::abs(into.dot(frame.up)), 1.0, 1e-12);
  EXPECT_FALSE(face_it_sits_on(frame, body, on_edge, &into));
  EXPECT_FALSE(face_it_sits_on(frame, body, on_top + 0.15 * frame.up, &into));  // on another part, 15 cm up
  EXPECT_FALSE(face_it_sits_on(BodyFrame{}, body, on_front, &into));  // a round body has no faces

  // Its press no track could type, where the hand's grip alone moved, its
  // axis that grip's wander, 5 degrees off up: into the front, not up.
  const Vector3d read = tilted(frame.up, frame.u, 5);
  JointEstimate press = joint("prismatic", read);
  press.range_hi = 0.003;
  press.motion_untyped = true;
  AxisPrior prior = apply_axis_prior(frame, &press, nullptr, &body, &on_front);
  EXPECT_TRUE(prior.by_body_face);
  EXPECT_EQ(prior.axis, "v");
  EXPECT_NEAR(std::abs(press.axis.dot(frame.v)), 1.0, 1e-12);
  // A press a track typed keeps the body's axis nearest its estimate.
  JointEstimate typed = joint("prismatic", read);
  typed.range_hi = 0.003;
  prior = apply_axis_prior(frame, &typed, nullptr, &body, &on_front);
  EXPECT_FALSE(prior.by_body_face);
  EXPECT_EQ(prior.axis, "up");
  // Its range is the hand's wander (a grip sliding 5 cm over a button whose
  // own track showed no motion): into the face all the same.
  JointEstimate wandered = joint("prismatic", read);
  wandered.range_hi = 0.05;
  wandered.motion_untyped = true;
  EXPECT_TRUE(apply_axis_prior(frame, &wandered, nullptr, &body, &on_front).by_body_face);
  // A knob's turn no track typed, the grip's turn a fingertip's wander 5
  // degrees off up (seed 0's s0039 dial): about the front's normal too
  // (efc infer passes the body for parts named for a press or a knob,
  // face_turn_named). A lever, named for a turn along its face, gets no
  // body: the body's axis nearest its estimate.
  JointEstimate knob = joint("revolute", read);
  knob.motion_untyped = true;
  prior = apply_axis_prior(frame, &knob, nullptr, &body, &on_front);
  EXPECT_TRUE(prior.by_body_face);
  EXPECT_EQ(prior.axis, "v");
  EXPECT_NEAR(std::abs(knob.axis.dot(frame.v)), 1.0, 1e-12);
  JointEstimate lever = joint("revolute", read);
  lever.motion_untyped = true;
  prior = apply_axis_prior(frame, &lever);
  EXPECT_FALSE(prior.by_body_face);
  EXPECT_EQ(prior.axis, "up");
  // A knob a track typed keeps the body's axis nearest its estimate.
  JointEstimate turned = joint("revolute", read);
  EXPECT_EQ(apply_axis_prior(frame, &turned, nullptr, &body, &on_front).axis, "up");
}

TEST(PipelineInferAxisPrior, OnARoundBodyOnlyUpIsAPrior) {
  BodyFrame round;  // not found: a drum's
  // The world's x is not the body's: a slide 10 degrees off it is kept.
  JointEstimate slide = joint("prismatic", tilted(Vector3d::UnitX(), Vector3d::UnitZ(), 10));
  const Vector3d read = slide.axis;
  EXPECT_TRUE(apply_axis_prior(round, &slide).axis.empty());
  EXPECT_EQ(slide.axis, read);
  // Nor does a press's face choose: up is the only axis there is.
  Cloud face;
  for (int i = 0; i < 200; ++i) face.points.emplace_back(0.0001 * i, 0, 0), face.normals.emplace_back(0, -1, 0);
  JointEstimate press = joint("prismatic", tilted(Vector3d::UnitY(), Vector3d::UnitZ(), 40));
  press.range_hi = 0.004;
  EXPECT_TRUE(apply_axis_prior(round, &press, &face).axis.empty());
  // Gravity's up is a prior on any body: a lid's spin 10 degrees off it is up.
  JointEstimate lid = joint("revolute", -tilted(Vector3d::UnitZ(), Vector3d::UnitY(), 10));
  EXPECT_EQ(apply_axis_prior(round, &lid).axis, "up");
  EXPECT_NEAR(lid.axis.dot(-Vector3d::UnitZ()), 1.0, 1e-12);
}

}  // namespace
