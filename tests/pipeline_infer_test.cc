// The stages of efc infer on made-up inputs with known answers: the
// visibility of a motion on a surface, the joint chosen from a part's
// registered poses (also when some registrations flipped the part) or from
// the hand alone, a still part staying fixed, which part the hand holds, the
// mean of rigid transforms, spec names and the spec assembled (an unseen
// effector's stand-in).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <set>

#include <unistd.h>

#include "compiler/core/load.h"
#include "pipeline/infer/ego_motion.h"
#include "pipeline/infer/grip_track.h"
#include "pipeline/infer/hand_contacts.h"
#include "pipeline/infer/joint_estimate.h"
#include "pipeline/infer/joint_names.h"
#include "pipeline/infer/spec_assembly.h"

namespace {

using namespace efc::pipeline;
using Eigen::Vector3d;
constexpr double kPi = 3.14159265358979323846;

// A ring (surface of revolution about z) with outward normals.
Cloud ring(double radius, double height) {
  Cloud c;
  for (int i = 0; i < 72; ++i)
    for (int k = 0; k < 5; ++k) {
      const double a = 2 * kPi * i / 72;
      c.points.push_back(Vector3d(radius * std::cos(a), radius * std::sin(a), height * k / 4));
      c.normals.push_back(Vector3d(std::cos(a), std::sin(a), 0));
    }
  return c;
}

// The faces of a box (half sizes `half`) centred at `centre`, outward normals.
Cloud box_faces(const Vector3d& half, const Vector3d& centre, int divisions = 8) {
  Cloud c;
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-1, 1})
      for (int i = 0; i <= divisions; ++i)
        for (int j = 0; j <= divisions; ++j) {
          Vector3d p, n = Vector3d::Zero();
          const int u = (axis + 1) % 3, v = (axis + 2) % 3;
          p[axis] = side * half[axis];
          p[u] = -half[u] + 2 * half[u] * i / divisions;
          p[v] = -half[v] + 2 * half[v] * j / divisions;
          n[axis] = side;
          c.points.push_back(p + centre);
          c.normals.push_back(n);
        }
  return c;
}

// A door-like panel: the faces of a 0.6 x 0.02 x 0.8 box.
Cloud panel() { return box_faces(Vector3d(0.3, 0.01, 0.4), Vector3d(0.3, 0, 0.4), 10); }

// An empty track of part 0 with `model`, its reference the first frame.
PartTrack track_of(const Cloud& model) {
  PartTrack t;
  t.part = 0;
  t.reference_frame = 0;
  t.model = model;
  return t;
}

// Two strokes of `height` starting at frames `first` and `second`: each
// ramps up over `ramp` frames, holds `hold`, ramps back; 0 elsewhere.
double two_strokes(int f, int first, int second, double height, int ramp, int hold) {
  for (int start : {first, second}) {
    const int u = f - start;
    if (u >= 0 && u < ramp) return height * u / ramp;
    if (u >= ramp && u < ramp + hold) return height;
    if (u >= ramp + hold && u < 2 * ramp + hold) return height * (2 * ramp + hold - u) / ramp;
  }
  return 0.0;
}

// A part track whose motion is a turn of q(f) about `axis` through `origin`.
PartTrack turning(const Cloud& model, const Vector3d& axis, const Vector3d& origin, double amplitude, int frames,
                  double noise, unsigned seed) {
  PartTrack t = track_of(model);
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, noise);
  for (int f = 0; f < frames; ++f) {
    const double q = amplitude * std::sin(kPi * f / (frames - 1));
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(q, axis).toRotationMatrix();
    T.translation() = origin - T.linear() * origin + Vector3d(g(rng), g(rng), g(rng));
    t.motion.push_back(T);
    t.tracked.push_back(true);
    t.rmse.push_back(0.001), t.inliers.push_back(1), t.conditioning.push_back(1);
  }
  t.frames_tracked = frames;
  return t;
}

std::vector<Vector3d> no_hand(int frames) {
  return std::vector<Vector3d>(frames, Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
}

TEST(PipelineInfer, VisibilityTellsASpinningRingFromATurningDoor) {
  const Cloud r = ring(0.03, 0.02);
  EXPECT_LT(visibility(r, "revolute", Vector3d::UnitZ(), Vector3d::Zero()), 0.01);
  EXPECT_LT(visibility(r, "prismatic", Vector3d::UnitZ(), Vector3d::Zero()), 0.01);
  EXPECT_GT(visibility(r, "revolute", Vector3d::UnitX(), Vector3d::Zero()), 0.5);
  const Cloud door = panel();
  EXPECT_GT(visibility(door, "revolute", Vector3d::UnitZ(), Vector3d::Zero()), kMinVisibility);
  EXPECT_GT(visibility(door, "prismatic", Vector3d::UnitY(), Vector3d::Zero()), kMinVisibility);
}

TEST(PipelineInfer, AKnobTurnsAboutItselfADoorBesideIt) {
  // The ring turns about its own axis; the door about a line along its edge.
  EXPECT_TRUE(turns_about_itself(ring(0.03, 0.02), Vector3d::UnitZ(), Vector3d(0.002, -0.001, 0)));
  EXPECT_FALSE(turns_about_itself(panel(), Vector3d::UnitZ(), Vector3d::Zero()));
  // The same door about a vertical line through its middle would turn about itself.
  EXPECT_TRUE(turns_about_itself(panel(), Vector3d::UnitZ(), Vector3d(0.3, 0, 0)));
}

// A part track with its registration's information: each frame's Hessian
// says every direction is known to 5 mrad and 1 mm (the shape holds the
// spin, a little), about the model's centroid.
void with_information(PartTrack* t) {
  const Vector3d c = centroid(t->model);
  Eigen::Matrix<double, 6, 1> d;
  d << Vector3d::Constant(1 / (0.005 * 0.005)), Vector3d::Constant(1 / (0.001 * 0.001));
  for (size_t f = 0; f < t->motion.size(); ++f) {
    t->hessian.push_back(Eigen::Matrix<double, 6, 6>(d.asDiagonal()) * t->rmse[f] * t->rmse[f]);
    t->hessian_center.push_back(c);
    t->hessian_scale.push_back(0.05);
  }
}

// A round button 6 cm across on a face (normal z): its rim, its front and
// a low ridge across the front, which is all that shows a turn. The front
// sampled on `front_rings` circles: 5 show it about as much as the rim
// and its ridge, 8 more, as a camera in front of the button sees it.
Cloud ridged_button(int front_rings = 5) {
  Cloud c = ring(0.03, 0.01);
  for (int i = 1; i <= front_rings; ++i)
    for (int k = 0; k < 36; ++k) {
      const double a = 2 * kPi * k / 36, r = 0.03 * i / front_rings;
      c.points.push_back(Vector3d(r * std::cos(a), r * std::sin(a), 0.01));
      c.normals.push_back(Vector3d::UnitZ());
    }
  for (int i = 0; i < 12; ++i)
    for (int h = 0; h < 3; ++h)
      for (int side : {-1, 1}) {
        c.points.push_back(Vector3d(side * 0.002, -0.024 + 0.004 * i, 0.011 + 0.002 * h));
        c.normals.push_back(Vector3d(side, 0, 0));
      }
  return c;
}

TEST(PipelineInfer, AButtonsRegistrationThatSlipsRoundItsAxisStillShowsThePress) {
  // The button's registration slips round its axis by a random walk,
  // and it is pressed 8 mm along the axis twice. Its shape barely shows a
  // turn, so the slip is not taken for a knob's turn.
  const int frames = 150;
  const Vector3d normal = Vector3d::UnitZ();
  const Cloud model = ridged_button(8);
  auto button = [&](bool pressed, unsigned seed) {
    PartTrack t = turning(model, normal, Vector3d::Zero(), 0.0, frames, 0.0003, seed);
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0, 1);
    double slip = 0;
    for (int f = 0; f < frames; ++f) {
      slip += 0.03 * g(rng);
      const bool in = pressed && ((f >= 40 && f < 56) || (f >= 100 && f < 116));
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = Eigen::AngleAxisd(slip, normal).toRotationMatrix();
      T.translation() = t.motion[f].translation() + (in ? -0.008 : 0.0) * normal;
      t.motion[f] = T;
    }
    with_information(&t);
    return t;
  };
  const double shows = visibility(model, "revolute", normal, Vector3d::Zero());
  ASSERT_GT(shows, kMinVisibility);
  ASSERT_LT(shows, kSlipVisibility);
  // Pressed by a function (no hand operates it): the hinge's own slide
  // shows the press. (A receptor's press shows past its slip first:
  // AReceptorsPressShowsPastItsSlip.)
  const JointEstimate pressed = estimate_joint(button(true, 31), no_hand(frames), false);
  EXPECT_EQ(pressed.type, "prismatic");
  EXPECT_TRUE(pressed.slide_over_turn);
  EXPECT_LT(std::acos(std::min(1.0, std::abs(pressed.axis.dot(normal)))), 0.1);
  EXPECT_NEAR(pressed.range_hi - pressed.range_lo, 0.008, 0.002);
  // Unpressed, the slip is all the track shows: a turn, not a slide.
  const JointEstimate turned = estimate_joint(button(false, 32), no_hand(frames));
  EXPECT_EQ(turned.type, "revolute");
  EXPECT_FALSE(turned.slide_over_turn);
  EXPECT_FALSE(turned.press_past_slip);
  const JointEstimate operated = estimate_joint(button(true, 31), no_hand(frames));
  EXPECT_EQ(operated.type, "prismatic");
  EXPECT_TRUE(operated.press_past_slip);
}

TEST(PipelineInfer, AnEffectorsRegistrationThatSlipsRoundItselfLeavesItFixed) {
  // A round indicator nobody operates: its registration slips round its own
  // axis by a random walk, a turn its shape barely shows. As an effector it
  // stays fixed (the turn is the slip); the same track on a receptor is a
  // knob's turn. A door driven about a hinge beside it still turns.
  const int frames = 150;
  const Vector3d normal = Vector3d::UnitZ();
  PartTrack t = turning(ridged_button(), normal, Vector3d::Zero(), 0.0, frames, 0.0003, 41);
  std::mt19937 rng(41);
  std::normal_distribution<double> g(0, 1);
  double slip = 0;
  for (int f = 0; f < frames; ++f) {
    slip += 0.03 * g(rng);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(slip, normal).toRotationMatrix();
    T.translation() = t.motion[f].translation();
    t.motion[f] = T;
  }
  with_information(&t);
  const JointEstimate led = estimate_joint(t, no_hand(frames), false);
  EXPECT_EQ(led.type, "fixed");
  EXPECT_TRUE(led.turn_taken_for_slip);
  EXPECT_TRUE(led.q.empty());
  const JointEstimate knob = estimate_joint(t, no_hand(frames), true);
  EXPECT_EQ(knob.type.substr(0, 4) == "cont" ? "revolute" : knob.type, "revolute");
  EXPECT_FALSE(knob.turn_taken_for_slip);
  PartTrack door = turning(panel(), Vector3d::UnitZ(), Vector3d::Zero(), 1.2, frames, 0.001, 42);
  const JointEstimate driven = estimate_joint(door, no_hand(frames), false);
  EXPECT_EQ(driven.type, "revolute");
  EXPECT_FALSE(driven.turn_taken_for_slip);
}

TEST(PipelineInfer, ARoundShadeSeenFromOneSideSlipsRoundItselfToo) {
  // A lamp's round shade seen from one side only: the front half of a ring.
  // Its points' middle lies on the half seen, a radius off its axis, so
  // the turn is not about the part by turns_about_itself's test, yet its
  // shape shows the spin no better than a whole ring's: nobody operates it,
  // and the turn is the registration's slip (s0010's lamp, typed
  // continuous through 15 rad).
  Cloud half;
  const Cloud whole = ring(0.06, 0.05);
  for (size_t i = 0; i < whole.size(); ++i)
    if (whole.points[i].y() < 0) half.points.push_back(whole.points[i]), half.normals.push_back(whole.normals[i]);
  // A seam down its front, the little that shows the spin.
  for (int h = 0; h < 5; ++h)
    for (int side : {-1, 1}) {
      half.points.push_back(Vector3d(side * 0.002, -0.062, 0.0125 * h));
      half.normals.push_back(Vector3d(side, 0, 0));
    }
  EXPECT_FALSE(turns_about_itself(half, Vector3d::UnitZ(), Vector3d::Zero()));
  const double shown = visibility(half, "revolute", Vector3d::UnitZ(), Vector3d::Zero());
  EXPECT_GT(shown, kMinVisibility);
  EXPECT_LT(shown, kSlipVisibility);
  const int frames = 150;
  PartTrack t = turning(half, Vector3d::UnitZ(), Vector3d::Zero(), 0.0, frames, 0.0003, 43);
  std::mt19937 rng(43);
  std::normal_distribution<double> g(0, 1);
  double slip = 0;
  for (int f = 0; f < frames; ++f) {
    slip += 0.05 * g(rng);
    t.motion[f].linear() = Eigen::AngleAxisd(slip, Vector3d::UnitZ()).toRotationMatrix();
  }
  with_information(&t);
  const JointEstimate shade = estimate_joint(t, no_hand(frames), false);
  EXPECT_EQ(shade.type, "fixed");
  EXPECT_TRUE(shade.turn_taken_for_slip);
  // Operated, the same turn is a knob's.
  const JointEstimate knob = estimate_joint(t, no_hand(frames), true);
  EXPECT_NE(knob.type, "fixed");
}

// `c` with each normal tilted by the depth's noise as a fused model's are
// (about 35 degrees, from a pixel's neighbours in its depth image).
Cloud with_noisy_normals(Cloud c, std::mt19937& rng) {
  std::normal_distribution<double> g(0, 0.6);
  for (Vector3d& n : c.normals) n = (n + Vector3d(g(rng), g(rng), g(rng))).normalized();
  return c;
}

// A pot seen from the front: the near half of a cylinder (radius 9 cm,
// height 12 cm) and its top, points 5 mm apart, its normals noisy
// (with_noisy_normals).
Cloud pot_with_noisy_normals(unsigned seed) {
  Cloud c;
  auto add = [&](const Vector3d& p, const Vector3d& n) {
    c.points.push_back(p);
    c.normals.push_back(n);
  };
  const double r = 0.09, h = 0.12, step = 0.005;
  for (double a = kPi; a < 2 * kPi; a += step / r)
    for (double z = 0; z <= h; z += step) add(Vector3d(r * std::cos(a), r * std::sin(a), z), Vector3d(std::cos(a), std::sin(a), 0));
  for (double x = -r; x <= r; x += step)
    for (double y = -r; y <= r; y += step)
      if (x * x + y * y <= r * r) add(Vector3d(x, y, h), Vector3d::UnitZ());
  std::mt19937 rng(seed);
  return with_noisy_normals(c, rng);
}

TEST(PipelineInfer, APotsSpinIsReadOnItsSurfaceNotOnItsNoisyNormals) {
  // Seed 1's s0002 pot: nobody operates it, its registration spins it by
  // a random walk about its axis, and its fused normals, noisy, show that
  // spin half as plainly as a generic turn. Its surface's normals
  // (with_surface_normals, shape_visibility) barely show it: the turn is the slip, and the
  // pot stays fixed. A door driven about a hinge beside it, its normals as
  // noisy, still turns.
  const Cloud pot = pot_with_noisy_normals(51);
  const Vector3d axis = Vector3d::UnitZ();
  ASSERT_GE(visibility(pot, "revolute", axis, Vector3d::Zero()), kSlipVisibility);
  EXPECT_LT(visibility(with_surface_normals(pot), "revolute", axis, Vector3d::Zero()), 0.2);
  EXPECT_LT(shape_visibility(pot, "revolute", axis, Vector3d::Zero()), 0.2);
  const int frames = 150;
  PartTrack t = turning(pot, axis, Vector3d::Zero(), 0.0, frames, 0.0003, 52);
  std::mt19937 rng(52);
  std::normal_distribution<double> g(0, 1);
  double slip = 0;
  for (int f = 0; f < frames; ++f) {
    slip += 0.05 * g(rng);
    t.motion[f].linear() = Eigen::AngleAxisd(slip, axis).toRotationMatrix();
  }
  with_information(&t);
  const JointEstimate spun = estimate_joint(t, no_hand(frames), false);
  EXPECT_EQ(spun.type, "fixed");
  EXPECT_TRUE(spun.turn_taken_for_slip);
  const Cloud door = with_noisy_normals(panel(), rng);
  PartTrack swung = turning(door, axis, Vector3d::Zero(), 1.2, frames, 0.001, 53);
  const JointEstimate driven = estimate_joint(swung, no_hand(frames), false);
  EXPECT_EQ(driven.type, "revolute");
  EXPECT_FALSE(driven.turn_taken_for_slip);
}

// A round part (`model`, axis z) the hand operates, whose registration
// spins it about its axis by a random walk of whole radians and wanders
// 2 mm across the axis; `pressed`: held 6 mm in along the axis for frames
// 40-59 and 95-114; `jumps`: thrown 6 mm one way or the other along the
// axis for one frame in 23, as a knob's slipping registration is.
// `slip_step`: the random walk's step (rad a frame); `across`: the wander
// across the axis (m); the turn is about a line along the axis through
// `pivot` (the part's middle by default, a line beside it otherwise); and
// the part slides along x by slide(f) (a slider's knob in its slot).
PartTrack slipping_round_part(const Cloud& model, bool pressed, bool jumps, int frames, unsigned seed,
                              double slip_step = 0.6, double across = 0.002,
                              const Vector3d& pivot = Vector3d::Zero(),
                              const std::function<double(int)>& slide = nullptr) {
  const Vector3d axis = Vector3d::UnitZ();
  PartTrack t = turning(model, axis, Vector3d::Zero(), 0.0, frames, 0.0, seed);
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, 1);
  double slip = 0;
  for (int f = 0; f < frames; ++f) {
    slip += slip_step * g(rng);
    const bool in = pressed && ((f >= 40 && f < 60) || (f >= 95 && f < 115));
    const double jump = jumps && f % 23 == 11 ? (f % 2 ? 0.006 : -0.006) : 0.0;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(slip, axis).toRotationMatrix();
    T.translation() = pivot - T.linear() * pivot + Vector3d(across * g(rng), across * g(rng), 0.0005 * g(rng)) +
                      (jump - (in ? 0.006 : 0.0)) * axis + (slide ? slide(f) : 0.0) * Vector3d::UnitX();
    t.motion[f] = T;
  }
  with_information(&t);
  return t;
}

TEST(PipelineInfer, AReceptorsPressShowsPastItsSlip) {
  // A round button the hand operates: its registration spins it about its
  // axis by whole radians from frame to frame and wanders 2 mm across the
  // axis, and it is pressed 6 mm in twice. A hinge through it explains such
  // poses better than a slide does; its centre along its symmetry axis,
  // held one way for a run of frames, shows the press. A knob's slipping
  // registration that jumps both ways along the axis, a frame at a time,
  // is no press.
  const int frames = 150;
  const Vector3d normal = Vector3d::UnitZ();
  auto round_part = [&](bool pressed, bool jumps, unsigned seed) {
    return slipping_round_part(ridged_button(8), pressed, jumps, frames, seed);
  };
  const JointEstimate button = estimate_joint(round_part(true, false, 71), no_hand(frames), true);
  EXPECT_TRUE(button.press_past_slip);
  EXPECT_EQ(button.type, "prismatic");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(button.axis.dot(normal)))), 0.1);
  EXPECT_NEAR(button.range_hi - button.range_lo, 0.006, 0.002);
  ASSERT_EQ(static_cast<int>(button.q.size()), frames);
  EXPECT_GT(button.q[50] - button.q[20], 0.004);  // in at the press, out before
  for (const bool jumps : {false, true}) {
    const JointEstimate knob = estimate_joint(round_part(false, jumps, 72), no_hand(frames), true);
    EXPECT_FALSE(knob.press_past_slip) << jumps;
    EXPECT_NE(knob.type, "prismatic") << jumps;
  }
  // Nobody operates an effector: its slip is no press either.
  EXPECT_FALSE(estimate_joint(round_part(true, false, 71), no_hand(frames), false).press_past_slip);
  // Where the hand's contacts trace a turn about the part (5 cm out, 1.5
  // rad and back), the hand turned it: whatever its centre did, no press.
  std::vector<Vector3d> turning_hand = no_hand(frames);
  for (int f = 20; f < 130; ++f) {
    const double a = 1.5 * std::sin(kPi * (f - 20) / 110.0);
    turning_hand[f] = Vector3d(0.05 * std::cos(a), 0.05 * std::sin(a), 0.012);
  }
  const JointEstimate turned = estimate_joint(round_part(true, false, 71), turning_hand, true);
  EXPECT_EQ(turned.from_hand.type, "revolute");
  EXPECT_FALSE(turned.press_past_slip);
  EXPECT_FALSE(estimate_joint(round_part(true, false, 71), turning_hand, true, nullptr, "prismatic").press_past_slip);
  // Contacts 1.2 cm from the part's middle, under a centimetre of detector
  // noise, that trace 2 rad about it: a fingertip on a button, whose noise a
  // hinge through it fits by radians. No lever arm, no turn: the press shows.
  std::mt19937 rng(76);
  std::normal_distribution<double> g(0, 0.01);
  std::vector<Vector3d> fingertip = no_hand(frames);
  for (int f = 20; f < 130; ++f) {
    const double a = 2.0 * std::sin(kPi * (f - 20) / 110.0);
    fingertip[f] = Vector3d(0.012 * std::cos(a) + g(rng), 0.012 * std::sin(a) + g(rng), 0.012 + 0.3 * g(rng));
  }
  const JointEstimate pressed = estimate_joint(round_part(true, false, 71), fingertip, true);
  ASSERT_EQ(pressed.from_hand.type, "revolute");
  EXPECT_LT(pressed.from_hand.radius, 0.03);
  EXPECT_TRUE(pressed.press_past_slip);
  EXPECT_EQ(pressed.type, "prismatic");
}

TEST(PipelineInfer, ADrivenRamsRiseShowsPastItsSpin) {
  // A pump's ram nobody operates: a round part (axis z, a ridge across its
  // top, a tab at its rim) that the pumping raises 6 mm at frame 40 and
  // 6 mm more at frame 90, and that stays up. Its registration spins it
  // about its axis by whole radians and wanders 2 mm across the axis, which
  // a hinge through it explains better than a slide does (without the rule
  // it came out continuous, through 12 rad). Its poses less their twist
  // about that axis, along it alone, show the rise: a slide along the axis.
  const int frames = 150;
  const Vector3d axis = Vector3d::UnitZ();
  Cloud model = ridged_button(8);
  const Cloud tab = box_faces(Vector3d(0.01, 0.004, 0.005), Vector3d(0.04, 0, 0.005), 4);
  model.points.insert(model.points.end(), tab.points.begin(), tab.points.end());
  model.normals.insert(model.normals.end(), tab.normals.begin(), tab.normals.end());
  // The tab shows the spin about as a generic turn shows, past what a slip
  // rule reads as barely shown (the suite's rams' fused models: 0.5 to 1.7).
  ASSERT_GT(visibility(model, "revolute", axis, Vector3d::Zero()), kSlipVisibility);
  // drift: a random walk along the axis (m per frame) in place of the rise.
  auto spinning = [&](bool rises, double drift, unsigned seed) {
    PartTrack t = turning(model, axis, Vector3d::Zero(), 0.0, frames, 0.0, seed);
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0, 1);
    double spin = 0, along = 0;
    for (int f = 0; f < frames; ++f) {
      spin += 0.6 * g(rng);
      along += drift * g(rng);
      const double rise = rises ? 0.006 * ((f >= 40) + (f >= 90)) : along;
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = Eigen::AngleAxisd(spin, axis).toRotationMatrix();
      T.translation() = Vector3d(0.002 * g(rng), 0.002 * g(rng), 0.0005 * g(rng)) + rise * axis;
      t.motion[f] = T;
    }
    with_information(&t);
    return t;
  };
  const JointEstimate ram = estimate_joint(spinning(true, 0, 91), no_hand(frames), false);
  EXPECT_EQ(ram.from_part.type, "revolute");  // the whole poses: the spin
  EXPECT_TRUE(ram.slide_past_spin);
  EXPECT_EQ(ram.type, "prismatic");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(ram.axis.dot(axis)))), 0.1);
  EXPECT_NEAR(ram.range_hi - ram.range_lo, 0.012, 0.003);
  ASSERT_EQ(static_cast<int>(ram.q.size()), frames);
  EXPECT_NEAR(ram.q[120] - ram.q[20], 0.012, 0.003);  // up twice, and still up
  EXPECT_NEAR(ram.q[60] - ram.q[20], 0.006, 0.002);
  // A fixed part whose registration also wanders along its axis (a random
  // walk of half a millimetre a frame, a spout's or a lamp's) is not
  // sliding: one seed in three passes for a slide without
  // kSlidePastSpinEvidence.
  for (unsigned seed : {92u, 93u, 94u}) {
    const JointEstimate still = estimate_joint(spinning(false, 0.0005, seed), no_hand(frames), false);
    EXPECT_FALSE(still.slide_past_spin) << seed;
    EXPECT_NE(still.type, "prismatic") << seed;
  }
}

TEST(PipelineInfer, AButtonWhosePressDoesNotShowIsPressedByItsName) {
  // The slipping round part with no press held along its axis (a press of
  // two millimetres is lost so in the noise): its track shows it moved, by
  // a turn its shape cannot show plainly, and where its name says a slide
  // it is pressed along the turn's axis, typed by its name, with a low
  // confidence. Named a knob, or nothing, it is not.
  const int frames = 150;
  for (const bool jumps : {false, true}) {
    const PartTrack t = slipping_round_part(ridged_button(8), false, jumps, frames, 72);
    const JointEstimate button = estimate_joint(t, no_hand(frames), true, nullptr, "prismatic");
    EXPECT_TRUE(button.press_past_slip) << jumps;
    EXPECT_TRUE(button.type_from_name) << jumps;
    EXPECT_EQ(button.type, "prismatic") << jumps;
    EXPECT_LE(button.confidence, 0.25) << jumps;
    EXPECT_LT(std::acos(std::min(1.0, std::abs(button.axis.dot(Vector3d::UnitZ())))), 0.1) << jumps;
    for (const std::string named : {"revolute", ""}) {
      const JointEstimate knob = estimate_joint(t, no_hand(frames), true, nullptr, named);
      EXPECT_NE(knob.type, "prismatic") << jumps << named;
      EXPECT_FALSE(knob.type_from_name) << jumps << named;
    }
    // Nobody operates an effector: no press, whatever its name.
    EXPECT_FALSE(estimate_joint(t, no_hand(frames), false, nullptr, "prismatic").press_past_slip) << jumps;
  }
  // A press that shows is no name's: the flag stays off.
  const JointEstimate shown =
      estimate_joint(slipping_round_part(ridged_button(8), true, false, frames, 71), no_hand(frames), true, nullptr, "prismatic");
  EXPECT_TRUE(shown.press_past_slip);
  EXPECT_FALSE(shown.type_from_name);
}

// A round button (axis z) whose registration turns it by a random walk of
// half radians about a line along its axis 4 cm beside it (seed 0's s0044
// light button: its hinge fitted 3 cm beside it, and its rim and ridge show
// that turn plainly), pressed 6 mm in for frames 40-59 and 95-114, and
// slid along x by slide(f) (a slider's knob in its slot; 0 for a button).
PartTrack slipping_beside(int frames, unsigned seed, const std::function<double(int)>& slide) {
  return slipping_round_part(ridged_button(8), true, false, frames, seed, 0.3, 0.001, Vector3d(0.04, 0, 0), slide);
}

TEST(PipelineInfer, AButtonWhoseSlipTurnsItAboutALineBesideItIsPressedByItsName) {
  // A hinge beside the button explains its poses best, so no slip about
  // itself reads its press; named a button, its face and its name say it
  // slides, along its symmetry axis (the hinge's, beside it, is the
  // slip's). Named a knob or nothing, it turns.
  const int frames = 150;
  const Vector3d axis = Vector3d::UnitZ();
  const PartTrack t = slipping_beside(frames, 73, [](int) { return 0.0; });
  const JointEstimate knob = estimate_joint(t, no_hand(frames), true, nullptr, "revolute");
  ASSERT_EQ(knob.from_part.type, "revolute");
  EXPECT_FALSE(turns_about_itself(t.model, knob.from_part.axis, knob.from_part.origin));
  EXPECT_FALSE(knob.press_past_slip);
  EXPECT_NE(knob.type, "prismatic");
  EXPECT_NE(estimate_joint(t, no_hand(frames), true, nullptr, "").type, "prismatic");
  const JointEstimate button = estimate_joint(t, no_hand(frames), true, nullptr, "prismatic");
  EXPECT_TRUE(button.press_past_slip);
  EXPECT_EQ(button.type, "prismatic");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(button.axis.dot(axis)))), 0.1);
  ASSERT_EQ(static_cast<int>(button.q.size()), frames);
  EXPECT_NEAR(button.q[50] - button.q[20], 0.006, 0.002);  // in at the press, out before
  EXPECT_NEAR(button.q[105] - button.q[80], 0.006, 0.002);
  // Nobody operates an effector: its slip is no press, whatever its name.
  EXPECT_FALSE(estimate_joint(t, no_hand(frames), false, nullptr, "prismatic").press_past_slip);
}

// A plain round button 6 cm across (rim and front, axis z, no ridge):
// nothing on it shows a turn about its axis. Its front is seen more than
// its rim, as a camera in front of it sees it.
Cloud plain_button() {
  Cloud c = ring(0.03, 0.01);
  for (int i = 1; i <= 12; ++i)
    for (int k = 0; k < 36; ++k) {
      const double a = 2 * kPi * k / 36, r = 0.03 * i / 12;
      c.points.push_back(Vector3d(r * std::cos(a), r * std::sin(a), 0.01));
      c.normals.push_back(Vector3d::UnitZ());
    }
  return c;
}

TEST(PipelineInfer, APressShowsPastATurnItsShapeCannotShowAtAll) {
  // A plain round button the hand operates, whose registration spins it by
  // whole radians about its axis: its shape shows that turn nowhere
  // (visibility about 0), so its own track shows no motion at all, and its
  // centre, held 6 mm in along its axis twice, still shows the press. A
  // lever's round handle (15 cm long, 2 cm thick, round about its length)
  // whose centre is held along its length the same way is no button: it
  // faces across that axis, not along it.
  const int frames = 150;
  const Vector3d axis = Vector3d::UnitZ();
  auto pressed = [&](const Cloud& model, unsigned seed) {
    return slipping_round_part(model, true, false, frames, seed);
  };
  ASSERT_LT(visibility(plain_button(), "revolute", axis, Vector3d::Zero()), kMinVisibility);
  const JointEstimate button = estimate_joint(pressed(plain_button(), 81), no_hand(frames), true);
  EXPECT_EQ(button.from_part.type, "revolute");
  EXPECT_TRUE(button.press_past_slip);
  EXPECT_EQ(button.type, "prismatic");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(button.axis.dot(axis)))), 0.1);
  EXPECT_NEAR(button.range_hi - button.range_lo, 0.006, 0.002);
  const JointEstimate handle = estimate_joint(pressed(ring(0.01, 0.15), 82), no_hand(frames), true);
  EXPECT_FALSE(handle.press_past_slip);
  EXPECT_NE(handle.type, "prismatic");
}

// A round shade (a ring 10 cm across, 8 cm tall, axis z) whose registration
// slips round its own axis by a random walk of whole radians, and that
// tilts (0.25 rad) about a pivot beside it (along y, 11 cm from its centre)
// or not at all.
PartTrack slipping_shade(double tilt, unsigned seed) {
  const int frames = 150;
  PartTrack t = track_of(ring(0.05, 0.08));
  const Vector3d c = centroid(t.model), pivot(0, 0, 0.15);
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, 1);
  double slip = 0;
  for (int f = 0; f < frames; ++f) {
    slip += 0.08 * g(rng);
    Eigen::Isometry3d spin = Eigen::Isometry3d::Identity(), swing = Eigen::Isometry3d::Identity();
    spin.linear() = Eigen::AngleAxisd(slip, Vector3d::UnitZ()).toRotationMatrix();
    spin.translation() = c - spin.linear() * c;
    swing.linear() = Eigen::AngleAxisd(tilt * std::sin(kPi * f / (frames - 1)), Vector3d::UnitY()).toRotationMatrix();
    swing.translation() = pivot - swing.linear() * pivot + 0.0005 * Vector3d(g(rng), g(rng), g(rng));
    t.motion.push_back(swing * spin);
    t.tracked.push_back(true);
    t.rmse.push_back(0.001), t.inliers.push_back(1), t.conditioning.push_back(1);
  }
  t.frames_tracked = frames;
  with_information(&t);
  return t;
}

TEST(PipelineInfer, ARoundShadesSwingShowsPastItsSlip) {
  Vector3d axis;
  ASSERT_TRUE(near_symmetry_axis(ring(0.05, 0.08), &axis));
  EXPECT_GT(std::abs(axis.z()), 0.99);
  EXPECT_FALSE(near_symmetry_axis(box_faces(Vector3d(0.05, 0.03, 0.02), Vector3d::Zero()), &axis));
  // Nobody operates the shade: its swing decides, about the pivot.
  const JointEstimate swung = estimate_joint(slipping_shade(0.25, 7), no_hand(150), false);
  ASSERT_EQ(swung.type, "revolute");
  EXPECT_TRUE(swung.swing_past_slip);
  EXPECT_LT(std::acos(std::min(1.0, std::abs(swung.axis.dot(Vector3d::UnitY())))), 0.15);  // not z, 1.57 away
  EXPECT_LT((swung.origin - Vector3d(0, swung.origin.y(), 0.15)).norm(), 0.01);
  EXPECT_NEAR(swung.range_hi - swung.range_lo, 0.25, 0.03);
  // A receptor's does not: a small button's tilts random-walk as well.
  EXPECT_FALSE(estimate_joint(slipping_shade(0.25, 7), no_hand(150), true).swing_past_slip);
  // Without the swing the slip is all there is: fixed, as before.
  const JointEstimate still = estimate_joint(slipping_shade(0.0, 8), no_hand(150), false);
  EXPECT_EQ(still.type, "fixed");
  EXPECT_FALSE(still.swing_past_slip);
}

// A flat square button (2.4 cm, 6 mm deep, its face's normal y) whose
// registration drifts 2 cm across its face, where only its thin sides hold
// it, while it is pressed 4 mm along its normal twice: the drift is the
// larger slide, but one its shape barely shows; the press is the joint.
// Its face (y = -3 mm, facing the camera) and a strip of its four sides
// (it stands 2 mm proud of the panel), sampled every 2 mm.
Cloud flat_button() {
  Cloud button;
  for (int i = -6; i <= 6; ++i)
    for (int k = -6; k <= 6; ++k) {
      button.points.push_back(Vector3d(0.002 * i, -0.003, 0.002 * k));
      button.normals.push_back(-Vector3d::UnitY());
    }
  for (int i = -6; i <= 6; ++i)
    for (int side : {-1, 1}) {
      button.points.push_back(Vector3d(side * 0.012, -0.002, 0.002 * i));
      button.normals.push_back(Vector3d(side, 0, 0));
      button.points.push_back(Vector3d(0.002 * i, -0.002, side * 0.012));
      button.normals.push_back(Vector3d(0, 0, side));
    }
  return button;
}

// Registered as the button's poses are, known to 3 mm across the face
// along x, to 1 mm along the normal.
void add_flat_pose(PartTrack* t, const Eigen::Isometry3d& T) {
  t->motion.push_back(T);
  t->tracked.push_back(true);
  t->rmse.push_back(0.001), t->inliers.push_back(1), t->conditioning.push_back(1);
  Eigen::Matrix<double, 6, 1> d;
  d << Vector3d::Constant(1 / (0.005 * 0.005)), 1 / (0.003 * 0.003), 1 / (0.001 * 0.001), 1 / (0.001 * 0.001);
  t->hessian.push_back(Eigen::Matrix<double, 6, 6>(d.asDiagonal()) * 0.001 * 0.001);
  t->hessian_center.push_back(Vector3d::Zero());
  t->hessian_scale.push_back(0.01);
}

// A button (`model`, face normal -y) registered over `frames` frames as
// it drifts 2 cm across its face (x) and back, pressed 4 mm in along the
// normal (`depth`; 0: never) for frames 40-59 and 100-119.
PartTrack drifting_pressed_button(const Cloud& model, int frames, double depth = 0.004) {
  PartTrack t = track_of(model);
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0, 1);
  for (int f = 0; f < frames; ++f) {
    const bool pressed = (f >= 40 && f < 60) || (f >= 100 && f < 120);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Vector3d(0.02 * std::sin(kPi * f / (frames - 1)) + 0.002 * g(rng),
                               (pressed ? depth : 0.0) + 0.0003 * g(rng), 0.0003 * g(rng));
    add_flat_pose(&t, T);
  }
  t.frames_tracked = frames;
  return t;
}

TEST(PipelineInfer, AFlatButtonsDriftAcrossItsFaceIsNotItsSlide) {
  const int frames = 150;
  PartTrack t = drifting_pressed_button(flat_button(), frames);
  EXPECT_LT(visibility(t.model, "prismatic", Vector3d::UnitX(), Vector3d::Zero()), kSlipVisibility);
  EXPECT_GT(visibility(t.model, "prismatic", Vector3d::UnitY(), Vector3d::Zero()), kSlipVisibility);
  const JointEstimate j = estimate_joint(t, no_hand(frames));
  ASSERT_EQ(j.type, "prismatic");
  EXPECT_EQ(j.source, "part");
  EXPECT_TRUE(j.plain_slide);
  EXPECT_GT(std::abs(j.axis.dot(Vector3d::UnitY())), 0.99) << j.axis.transpose();
  EXPECT_NEAR(j.range_hi - j.range_lo, 0.004, 0.0015);
  ASSERT_EQ(static_cast<int>(j.q.size()), frames);
  EXPECT_NEAR(std::abs(j.q[50] - j.q[80]), 0.004, 0.0015);  // pressed against at rest
}

TEST(PipelineInfer, AFlatPartNobodyPressesWhoseRegistrationDriftsAcrossItsFaceStaysFixed) {
  // The flat button's drift across its face, without its presses, on a
  // part nobody operates (a panel, a vent's grille: seed 1's s0014 and
  // s0016 panels): the slide its shape barely shows is the slip, and
  // along its normal, the slide its shape shows, it stays put. Pushed out
  // along the normal by a function, 8 mm, it still slides. (Typed on the
  // runs of frames along the normal alone, against the registration's
  // floor of a millimetre, two 4 mm pushes of 20 frames do not show; 6 mm
  // do.)
  const int frames = 150;
  const JointEstimate panel = estimate_joint(drifting_pressed_button(flat_button(), frames, 0.0), no_hand(frames), false);
  EXPECT_EQ(panel.type, "fixed");
  EXPECT_TRUE(panel.slide_taken_for_slip);
  EXPECT_TRUE(panel.registration_slipped());
  EXPECT_TRUE(panel.q.empty());
  const JointEstimate pushed = estimate_joint(drifting_pressed_button(flat_button(), frames, 0.008), no_hand(frames), false);
  EXPECT_EQ(pushed.type, "prismatic");
  EXPECT_FALSE(pushed.slide_taken_for_slip);
  // A receptor's drift (the hand presses it, or may): the rule is not its.
  const JointEstimate button = estimate_joint(drifting_pressed_button(flat_button(), frames, 0.0), no_hand(frames));
  EXPECT_FALSE(button.slide_taken_for_slip);
}

// A flat button whose sides stand `layers` rows deep behind its face:
// the deeper they are, the more its slides across the face show.
Cloud deep_button(int layers) {
  Cloud button = flat_button();
  for (int l = 1; l <= layers; ++l)
    for (int i = -6; i <= 6; ++i)
      for (int side : {-1, 1}) {
        button.points.push_back(Vector3d(side * 0.012, -0.002 + 0.001 * l, 0.002 * i));
        button.normals.push_back(Vector3d(side, 0, 0));
        button.points.push_back(Vector3d(0.002 * i, -0.002 + 0.001 * l, side * 0.012));
        button.normals.push_back(Vector3d(0, 0, side));
      }
  return button;
}

TEST(PipelineInfer, ADeepButtonsDriftAcrossItsFaceIsNotItsSlideEither) {
  // The flat button's drift and presses on a button with sides two rows
  // deep: its drift across the face shows more than a slip's would, but
  // less than a generic motion does and less than its press does. A
  // press goes where the shape shows it best.
  const int frames = 150;
  PartTrack t = drifting_pressed_button(deep_button(2), frames);
  const double across = visibility(t.model, "prismatic", Vector3d::UnitX(), Vector3d::Zero());
  EXPECT_GT(across, kSlipVisibility);
  EXPECT_LT(across, kPlainTurnVisibility);
  EXPECT_GT(visibility(t.model, "prismatic", Vector3d::UnitY(), Vector3d::Zero()), across);
  const JointEstimate j = estimate_joint(t, no_hand(frames));
  ASSERT_EQ(j.type, "prismatic");
  EXPECT_TRUE(j.plain_slide);
  EXPECT_GT(std::abs(j.axis.dot(Vector3d::UnitY())), 0.99) << j.axis.transpose();
  EXPECT_NEAR(j.range_hi - j.range_lo, 0.004, 0.0015);
  // A part nobody presses keeps the slide its track shows: a tray's or a
  // ram's slide along its length shows less than one across it does.
  const JointEstimate driven = estimate_joint(t, no_hand(frames), false);
  ASSERT_EQ(driven.type, "prismatic");
  EXPECT_FALSE(driven.plain_slide);
  EXPECT_GT(std::abs(driven.axis.dot(Vector3d::UnitX())), 0.9) << driven.axis.transpose();
}

// The same flat shape as a slider's knob, slid 6 cm along its face (x)
// and back twice: its shape barely shows that slide either, and alone it
// is taken for a drift. The hand holding it slides with it, 6 cm, further
// than any press: the slide is the motion.
TEST(PipelineInfer, ASliderTheHandSlidesAlongIsNotADrift) {
  const int frames = 150;
  auto slid = [](int f) { return two_strokes(f, 30, 90, 0.06, 10, 10); };
  PartTrack t = track_of(flat_button());
  std::mt19937 rng(17);
  std::normal_distribution<double> g(0, 1);
  for (int f = 0; f < frames; ++f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Vector3d(slid(f) + 0.002 * g(rng), 0.0003 * g(rng), 0.0003 * g(rng));
    add_flat_pose(&t, T);
  }
  t.frames_tracked = frames;
  const JointEstimate alone = estimate_joint(t, no_hand(frames));
  ASSERT_EQ(alone.type, "prismatic");
  EXPECT_TRUE(alone.plain_slide);
  std::vector<Vector3d> hand = no_hand(frames);
  for (int f = 20; f < 130; ++f) hand[f] = Vector3d(slid(f), -0.01, 0) + 0.007 * Vector3d(g(rng), g(rng), g(rng));
  const JointEstimate slider = estimate_joint(t, hand, true);
  ASSERT_EQ(slider.type, "prismatic");
  EXPECT_EQ(slider.source, "part");
  EXPECT_FALSE(slider.plain_slide);
  EXPECT_TRUE(slider.hand_slides_along);
  EXPECT_GT(std::abs(slider.axis.dot(Vector3d::UnitX())), 0.99) << slider.axis.transpose();
  EXPECT_NEAR(slider.range_hi - slider.range_lo, 0.06, 0.01);
}

TEST(PipelineInfer, ADoorsPosesGiveItsHinge) {
  const int frames = 90;
  const PartTrack t = turning(panel(), Vector3d::UnitZ(), Vector3d::Zero(), 1.2, frames, 0.001, 1);
  const JointEstimate j = estimate_joint(t, no_hand(frames));
  ASSERT_EQ(j.type, "revolute");
  EXPECT_EQ(j.source, "part");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(j.axis.dot(Vector3d::UnitZ())))), 0.02);
  // The origin lies on the hinge line (x = y = 0).
  EXPECT_LT(Eigen::Vector2d(j.origin.x(), j.origin.y()).norm(), 0.01);
  EXPECT_NEAR(j.range_hi - j.range_lo, 1.2, 0.05);
  ASSERT_EQ(static_cast<int>(j.q.size()), frames);
  EXPECT_NEAR(j.q.front(), 0.0, 1e-9);
}

// A door out of view for a while: q bridges the frames unseen (its poses'
// consumers need one in every frame); q_seen leaves them unknown (the
// templates' geometry signal: it may have opened and shut unseen).
TEST(PipelineInfer, AnUnseenDoorsPositionIsBridgedButNotSeen) {
  const int frames = 90;
  PartTrack t = turning(panel(), Vector3d::UnitZ(), Vector3d::Zero(), 1.2, frames, 0.001, 1);
  for (int f = 30; f < 50; ++f) t.tracked[f] = false;
  t.frames_tracked = frames - 20;
  const JointEstimate j = estimate_joint(t, no_hand(frames));
  ASSERT_EQ(j.type, "revolute");
  ASSERT_EQ(static_cast<int>(j.q.size()), frames);
  ASSERT_EQ(static_cast<int>(j.q_seen.size()), frames);
  for (int f = 0; f < frames; ++f) {
    EXPECT_TRUE(std::isfinite(j.q[f])) << f;
    if (f >= 30 && f < 50) {
      EXPECT_TRUE(std::isnan(j.q_seen[f])) << f;
    } else {
      EXPECT_EQ(j.q_seen[f], j.q[f]) << f;
    }
  }
}

// A door's samples turned 0.3 to 1.2 rad about its hinge (z), and four
// near the peak turned as far about an axis 70 degrees off it (s0056's
// misregistration, kept by the spike test): those four are the ones off
// the consensus. Small turns name no axis and stay; six off, or a track
// whose large turns share no one axis (a part tumbling in the tracker),
// have none.
TEST(PipelineInfer, SamplesTurnedAboutAnotherAxisAreFound) {
  const Vector3d off = Vector3d(-0.9, -0.4, -0.16).normalized();
  Track t;
  for (int k = 0; k < 30; ++k) {
    const double angle = 1.2 * std::sin(kPi * k / 29);
    const bool misregistered = k >= 13 && k < 17;
    const Vector3d axis = misregistered ? off : k % 7 == 3 ? Vector3d(0.1, 0, 1).normalized() : Vector3d::UnitZ();
    t.rotations.emplace_back(Eigen::AngleAxisd(misregistered ? 1.3 : angle, axis));
    t.positions.push_back(Vector3d::Zero());
  }
  EXPECT_EQ(turned_about_another_axis(t), (std::vector<size_t>{13, 14, 15, 16}));
  // Six off: no brief misregistration, but turns that share no one axis.
  for (int k : {12, 17}) t.rotations[k] = Eigen::AngleAxisd(1.3, off);
  EXPECT_TRUE(turned_about_another_axis(t).empty());
  Track tumbling;
  for (int k = 0; k < 12; ++k) {
    const Vector3d axis(std::cos(k), std::sin(2.0 * k), 0.5 * std::cos(3.0 * k));
    tumbling.rotations.emplace_back(Eigen::AngleAxisd(1.0, axis.normalized()));
    tumbling.positions.push_back(Vector3d::Zero());
  }
  EXPECT_TRUE(turned_about_another_axis(tumbling).empty());
}

// The same door through estimate_joint, with four frames near the peak of
// its swing turned about a line through its hinge 70 degrees off it: the
// hinge comes out within 0.05 rad of z, and frames it left out, if any, are
// among those four and unknown in what was seen.
TEST(PipelineInfer, FramesTurnedAboutAnotherAxisLeaveTheHingeAlone) {
  const int frames = 90;
  PartTrack t = turning(panel(), Vector3d::UnitZ(), Vector3d::Zero(), 1.2, frames, 0.001, 3);
  const Vector3d off_axis = Vector3d(-0.9, -0.4, -0.16).normalized();
  for (int f = 43; f < 47; ++f) {
    t.motion[f] = Eigen::Isometry3d::Identity();
    t.motion[f].linear() = Eigen::AngleAxisd(1.3 + 0.03 * (f - 43), off_axis).toRotationMatrix();
  }
  const JointEstimate j = estimate_joint(t, no_hand(frames));
  ASSERT_EQ(j.type, "revolute");
  EXPECT_GT(std::abs(j.axis.dot(Vector3d::UnitZ())), std::cos(0.05));
  ASSERT_EQ(static_cast<int>(j.q_seen.size()), frames);
  for (int f : j.frames_off_axis) {
    EXPECT_GE(f, 43);
    EXPECT_LT(f, 47);
    EXPECT_TRUE(std::isnan(j.q_seen[f])) << f;
  }
  EXPECT_NEAR(j.range_hi - j.range_lo, 1.2, 0.05);
}

// The axis points the way the part was actuated: a door swung 1.2 rad the
// negative way about +z and let go a little past its rest (a coin toss
// for a sign taken from the first sample to the last) is a hinge about -z
// with q from 0 at rest to +1.2, and the hand's q with it.
TEST(PipelineInfer, TheAxisPointsTheWayThePartWasActuated) {
  const int frames = 90;
  PartTrack t = track_of(panel());
  std::vector<Vector3d> hand = no_hand(frames);
  for (int f = 0; f < frames; ++f) {
    const double q = f < 60 ? -1.2 * std::sin(kPi * f / 59) : 0.05 * std::sin(kPi * (f - 59) / 30.0);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(q, Vector3d::UnitZ()).toRotationMatrix();
    t.motion.push_back(T);
    t.tracked.push_back(true);
    t.rmse.push_back(0.001), t.inliers.push_back(1), t.conditioning.push_back(1);
    hand[f] = T * Vector3d(0.55, -0.02, 0.4);  // the handle, held throughout
  }
  t.frames_tracked = frames;
  const JointEstimate j = estimate_joint(t, hand);
  ASSERT_EQ(j.type, "revolute");
  EXPECT_GT(j.axis.dot(-Vector3d::UnitZ()), 0.99);
  EXPECT_NEAR(j.range_lo, -0.05, 0.02);  // let go past its rest
  EXPECT_NEAR(j.range_hi, 1.2, 0.05);
  EXPECT_NEAR(j.q[30], 1.2, 0.05);
  ASSERT_EQ(j.q_hand.size(), j.q.size());
  EXPECT_NEAR(j.q_hand[30], 1.2, 0.1);
  // The motion at q is the door's: the handle at q = 1.2 is where frame 30 put it.
  const Vector3d handle = joint_motion(j, j.q[30]) * Vector3d(0.55, -0.02, 0.4);
  EXPECT_LT((handle - hand[30]).norm(), 0.01);
}

// The hand's contacts, the templates' second candidate for s_R, are
// oriented by their own positions: where the part's track is its
// registration's slip (a round knob's), its sign says nothing of the
// hand's. Here the door's track turns +1.2 rad about +z while the
// contacts at its edge turn the other way: the part's q still rises to
// +1.2, and the hand's too.
TEST(PipelineInfer, TheHandsContactsAreOrientedByTheirOwnTurn) {
  const int frames = 90;
  const PartTrack t = turning(panel(), Vector3d::UnitZ(), Vector3d::Zero(), 1.2, frames, 0.001, 5);
  std::vector<Vector3d> hand = no_hand(frames);
  for (int f = 0; f < frames; ++f) hand[f] = t.motion[f].inverse() * Vector3d(0.55, -0.02, 0.4);
  const JointEstimate j = estimate_joint(t, hand);
  ASSERT_EQ(j.type, "revolute");
  ASSERT_EQ(j.source, "part");
  EXPECT_NEAR(j.q[45], 1.2, 0.05);
  ASSERT_EQ(j.q_hand.size(), j.q.size());
  EXPECT_NEAR(j.q_hand[45], 1.2, 0.1);
}

// The hand's points read a turn only from a lever arm: held 1.5 cm from
// the axis (a knob's grip), a centimetre of detector error turns them by
// radians, so the templates get no second candidate from them; held at
// the door's edge they do.
TEST(PipelineInfer, TheHandReadsATurnOnlyFromALeverArm) {
  const int frames = 90;
  const PartTrack t = turning(panel(), Vector3d::UnitZ(), Vector3d::Zero(), 1.2, frames, 0.001, 5);
  std::mt19937 rng(6);
  std::normal_distribution<double> g(0, 0.007);
  for (double arm : {0.015, 0.5}) {
    std::vector<Vector3d> hand = no_hand(frames);
    for (int f = 0; f < frames; ++f)
      hand[f] = t.motion[f] * Vector3d(arm, -0.02, 0.4) + Vector3d(g(rng), g(rng), g(rng));
    const JointEstimate j = estimate_joint(t, hand);
    ASSERT_EQ(j.type, "revolute") << arm;
    ASSERT_EQ(j.source, "part") << arm;
    EXPECT_EQ(j.q_hand.empty(), arm < 0.03) << arm;
  }
}

TEST(PipelineInfer, AStillPartIsFixedAndASpinningRingToo) {
  const int frames = 60;
  const JointEstimate still = estimate_joint(turning(panel(), Vector3d::UnitZ(), Vector3d::Zero(), 0.0, frames, 0.0005, 2),
                                             no_hand(frames));
  EXPECT_EQ(still.type, "fixed");
  // Registration sliding round a ring's own axis is not a motion.
  const JointEstimate spin =
      estimate_joint(turning(ring(0.05, 0.02), Vector3d::UnitZ(), Vector3d::Zero(), 2.0, frames, 0.0005, 3),
                     no_hand(frames));
  EXPECT_EQ(spin.type, "fixed");
}

TEST(PipelineInfer, TheHandGivesTheJointTheShapeCannotShow) {
  // A round knob (a ring) the registration cannot see turning; the hand
  // holds its rim while turning it by 1.5 rad, seen with 8 mm noise.
  const int frames = 120;
  const Cloud knob = ring(0.03, 0.02);
  const PartTrack t = turning(knob, Vector3d::UnitZ(), Vector3d::Zero(), 0.0, frames, 0.0005, 4);
  std::vector<Vector3d> hand = no_hand(frames);
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0, 0.008);
  for (int f = 20; f < 100; ++f) {
    const double q = 1.5 * (f - 20) / 79.0;
    hand[f] = Vector3d(0.06 * std::cos(q), 0.06 * std::sin(q), 0.02) + Vector3d(g(rng), g(rng), g(rng));
  }
  const JointEstimate j = estimate_joint(t, hand);
  ASSERT_EQ(j.type, "revolute");
  EXPECT_EQ(j.source, "hand");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(j.axis.dot(Vector3d::UnitZ())))), 0.15);
  EXPECT_NEAR(j.range_hi - j.range_lo, 1.5, 0.3);
  // A name never overrules a motion that shows.
  const JointEstimate named = estimate_joint(t, hand, true, nullptr, "prismatic");
  EXPECT_EQ(named.type, "revolute");
  EXPECT_FALSE(named.type_from_name);
  // Without the hand, nothing shows the turn: fixed, not a guess.
  EXPECT_EQ(estimate_joint(t, no_hand(frames)).type, "fixed");
}

TEST(PipelineInfer, AReceptorTheHandHeldMovedEvenWhenNothingShowsIt) {
  // The round knob again, held at its centre (the hand's point barely
  // moves as it turns): neither track shows a motion. The hand held it, so
  // it was operated: a moving joint, flagged as assumed, low confidence.
  const int frames = 120;
  const PartTrack t = turning(ring(0.03, 0.02), Vector3d::UnitZ(), Vector3d::Zero(), 0.0, frames, 0.0005, 4);
  std::vector<Vector3d> hand = no_hand(frames);
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0, 0.003);
  for (int f = 20; f < 100; ++f) hand[f] = Vector3d(0, 0, 0.02) + Vector3d(g(rng), g(rng), g(rng));
  const JointEstimate held = estimate_joint(t, hand);
  EXPECT_TRUE(held.assumed_moving);
  EXPECT_NE(held.type, "fixed");
  EXPECT_LE(held.confidence, 0.5);
  EXPECT_EQ(static_cast<int>(held.q.size()), frames);
  EXPECT_FALSE(held.type_from_name);
  // Its name, where it names a joint, types it instead of two fits to
  // noise, with the same low confidence.
  for (const std::string named : {"prismatic", "revolute"}) {
    const JointEstimate by_name = estimate_joint(t, hand, true, nullptr, named);
    EXPECT_TRUE(by_name.assumed_moving);
    EXPECT_TRUE(by_name.type_from_name);
    // (a turn wider than a whole one comes out continuous)
    EXPECT_EQ(by_name.type == "prismatic" ? "prismatic" : by_name.type == "fixed" ? "fixed" : "revolute", named);
    EXPECT_LE(by_name.confidence, 0.5);
  }
  // Nobody held it: fixed, not a guess, whatever its name.
  const JointEstimate alone = estimate_joint(t, no_hand(frames), true, nullptr, "prismatic");
  EXPECT_EQ(alone.type, "fixed");
  EXPECT_FALSE(alone.assumed_moving);
  EXPECT_FALSE(alone.type_from_name);
  // A recording without the hand (no hands.txt) cannot say it was not
  // held: a receptor (operated) moves by the same assumption, its geometry
  // from its own track (its registration's noise turns it a little, as
  // any registration's does); a part no one operates stays fixed.
  PartTrack jittered = t;
  std::normal_distribution<double> tilt(0, 0.005);
  for (Eigen::Isometry3d& m : jittered.motion) {
    const Vector3d w(tilt(rng), tilt(rng), tilt(rng));
    m.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix() * m.linear();
  }
  const JointEstimate unrecorded = estimate_joint(jittered, no_hand(frames), true, nullptr, "revolute", false);
  EXPECT_TRUE(unrecorded.assumed_moving);
  EXPECT_TRUE(unrecorded.type_from_name);
  EXPECT_NE(unrecorded.type, "fixed");
  EXPECT_EQ(unrecorded.source, "part");
  EXPECT_LE(unrecorded.confidence, 0.5);
  EXPECT_EQ(static_cast<int>(unrecorded.q.size()), frames);
  const JointEstimate effector = estimate_joint(jittered, no_hand(frames), false, nullptr, "revolute", false);
  EXPECT_EQ(effector.type, "fixed");
  EXPECT_FALSE(effector.assumed_moving);
  // The hand's contacts reached it in two frames, too few for a track
  // (seed 1's s0027 paddle): held all the same, so it moved by the same
  // assumption, its geometry from its own track. Nobody's contacts, as
  // above, and it stays fixed.
  std::vector<Vector3d> touched = no_hand(frames);
  touched[50] = touched[51] = Vector3d(0, 0, 0.02);
  const JointEstimate brief = estimate_joint(jittered, touched, true, nullptr, "revolute");
  ASSERT_FALSE(brief.has_hand_track);
  EXPECT_EQ(brief.hand_samples, 2);
  EXPECT_TRUE(brief.assumed_moving);
  EXPECT_TRUE(brief.type_from_name);
  EXPECT_NE(brief.type, "fixed");
  EXPECT_EQ(brief.source, "part");
  EXPECT_LE(brief.confidence, 0.5);
  EXPECT_EQ(estimate_joint(jittered, no_hand(frames), true, nullptr, "revolute").type, "fixed");
  EXPECT_EQ(estimate_joint(jittered, touched, false, nullptr, "revolute").type, "fixed");  // not a receptor
}

TEST(PipelineInfer, APartsNameNamesItsJoint) {
  EXPECT_EQ(joint_named("button"), "prismatic");
  EXPECT_EQ(joint_named("speed_button"), "prismatic");
  EXPECT_TRUE(press_named("speed_button"));
  EXPECT_FALSE(press_named("fanSlider"));  // slides along its face
  EXPECT_TRUE(press_named("flow_up"));     // the button that raises the flow
  EXPECT_TRUE(press_named("volumeDown"));
  EXPECT_EQ(joint_named("flow_up"), "prismatic");
  EXPECT_FALSE(press_named("knob_left"));
  EXPECT_TRUE(face_turn_named("knob_left"));  // turned about the face it stands out of
  EXPECT_TRUE(face_turn_named("Dial"));
  EXPECT_FALSE(face_turn_named("lever"));     // about an axis along it
  EXPECT_FALSE(face_turn_named("thumbwheel"));  // edge out, its axis along the face
  EXPECT_FALSE(face_turn_named("button"));
  EXPECT_EQ(joint_named("fanSlider"), "prismatic");
  EXPECT_EQ(joint_named("knob_left"), "revolute");
  EXPECT_EQ(joint_named("Rocker"), "revolute");
  EXPECT_EQ(joint_named("button_knob"), "revolute");  // the last word that names one
  EXPECT_EQ(joint_named("knobs"), "revolute");        // a plural's s
  EXPECT_EQ(joint_named("power_switch"), "");          // a rocker, a toggle or a slide
  EXPECT_EQ(joint_named("handle"), "");
  EXPECT_EQ(joint_named(""), "");
}

// A round button or knob's track (the ridged button, axis z) whose
// registration slips round the axis by a random walk and shows nothing
// else: the hand hides its press, or its shape its turn.
PartTrack slipping(int frames, unsigned seed) {
  PartTrack t = turning(ridged_button(), Vector3d::UnitZ(), Vector3d::Zero(), 0.0, frames, 0.0003, seed);
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, 1);
  double slip = 0;
  for (int f = 0; f < frames; ++f) {
    slip += 0.03 * g(rng);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(slip, Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = t.motion[f].translation();
    t.motion[f] = T;
  }
  with_information(&t);
  return t;
}

// The grip's track: a hand (a palm-sized box above and beside the part's
// axis, and a finger-sized one on it) seen in frames [from, to) only,
// moving by motion(f).
PartTrack grip(int frames, int from, int to, const std::function<Eigen::Isometry3d(int)>& motion) {
  PartTrack t;
  t.reference_frame = from;
  t.model = concatenate(box_faces(Vector3d(0.04, 0.012, 0.045), Vector3d(0.02, 0.0, 0.07)),
                        box_faces(Vector3d(0.009, 0.009, 0.02), Vector3d(0.0, 0.0, 0.03)));
  for (int f = 0; f < frames; ++f) {
    const bool seen = f >= from && f < to;
    t.motion.push_back(seen ? motion(f) : Eigen::Isometry3d::Identity());
    t.tracked.push_back(seen);
    t.rmse.push_back(0.001), t.inliers.push_back(seen ? 1 : 0), t.conditioning.push_back(seen ? 1 : 0);
  }
  t.frames_tracked = to - from;
  with_information(&t);
  return t;
}

TEST(PipelineInfer, TheGripShowsTheTwistOrThePressTheRoundPartHides) {
  // A round part whose registration only slips round its axis. The hand
  // holds it in frames 20 to 130: twisting it 1.5 rad about its axis and
  // back (a knob), or pressing it 8 mm in along the axis twice (a button).
  // The grip's track tells the two apart; without it the slip is a turn.
  const int frames = 150;
  std::mt19937 rng(61);
  std::normal_distribution<double> g(0, 0.0005);
  auto noisy = [&](Eigen::Isometry3d T) {
    T.translation() += Vector3d(g(rng), g(rng), g(rng));
    return T;
  };
  // The fingers twist about an axis 0.2 rad off the knob's (they wobble
  // on it): the joint's axis is the part's own symmetry axis, which its
  // slipping registration gives, and the grip's twist about it its angle.
  const Vector3d wobbly(std::sin(0.2), 0, std::cos(0.2));
  const PartTrack twist = grip(frames, 20, 130, [&](int f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(1.5 * std::sin(kPi * (f - 20) / 110.0), wobbly).toRotationMatrix();
    return noisy(T);
  });
  const PartTrack press = grip(frames, 20, 130, [&](int f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    if ((f >= 40 && f < 60) || (f >= 90 && f < 110)) T.translation() = Vector3d(0, 0, -0.008);
    return noisy(T);
  });
  std::vector<Vector3d> hand = no_hand(frames);
  for (int f = 20; f < 130; ++f) hand[f] = Vector3d(0, 0, 0.012);
  const PartTrack part = slipping(frames, 62);

  const JointEstimate knob = estimate_joint(part, hand, true, &twist);
  EXPECT_EQ(knob.source, "grip");
  EXPECT_EQ(knob.type, "revolute");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(knob.axis.dot(Vector3d::UnitZ())))), 0.05);
  EXPECT_LT(Eigen::Vector2d(knob.origin.x(), knob.origin.y()).norm(), 0.01);
  EXPECT_NEAR(knob.range_hi - knob.range_lo, 1.5, 0.1);
  ASSERT_EQ(static_cast<int>(knob.q.size()), frames);
  EXPECT_NEAR(std::abs(knob.q[75] - knob.q[10]), 1.5, 0.1);  // held before the grasp

  const JointEstimate button = estimate_joint(part, hand, true, &press);
  EXPECT_EQ(button.source, "grip");
  EXPECT_EQ(button.type, "prismatic");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(button.axis.dot(Vector3d::UnitZ())))), 0.05);
  EXPECT_NEAR(button.range_hi - button.range_lo, 0.008, 0.002);

  // The grip only speaks for a part someone operates, and where the part's
  // own track cannot: without it the slip is the knob's turn.
  EXPECT_NE(estimate_joint(part, hand, false, &press).source, "grip");
  const JointEstimate alone = estimate_joint(part, hand, true, nullptr);
  EXPECT_EQ(alone.source, "part");
  EXPECT_EQ(alone.type.substr(0, 4) == "cont" ? "revolute" : alone.type, "revolute");
  // A door whose own track shows its turn keeps it, whatever the grip does.
  const PartTrack door = turning(panel(), Vector3d::UnitZ(), Vector3d::Zero(), 1.2, frames, 0.001, 63);
  const JointEstimate opened = estimate_joint(door, hand, true, &press);
  EXPECT_EQ(opened.source, "part");
  EXPECT_EQ(opened.type, "revolute");
}

TEST(PipelineInfer, AButtonNamedToSlideFollowsItsGripOnlyWhereItSlidesFurtherThanAPress) {
  // The button whose registration slips about a line beside it, held in
  // frames 20 to 130 by a grip that slides along x: 6 cm and back (a
  // slider's knob, moving with it along its slot), or 1.5 cm and back (a
  // finger's wander on a button pressed 6 mm along its axis). A grip
  // sliding further than a drifting press goes (kMaxDriftedPress) decides;
  // a finger's wander does not, and the press goes along the part's axis.
  const int frames = 150;
  std::mt19937 rng(74);
  std::normal_distribution<double> g(0, 0.0005);
  for (const double reach : {0.06, 0.015}) {
    const auto along = [&](int f) { return f < 20 || f >= 130 ? 0.0 : reach * std::sin(kPi * (f - 20) / 110.0); };
    const PartTrack grip_track = grip(frames, 20, 130, [&](int f) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.translation() = along(f) * Vector3d::UnitX() + Vector3d(g(rng), g(rng), g(rng));
      return T;
    });
    const PartTrack part = slipping_beside(frames, 75, [&](int f) { return reach > 0.02 ? along(f) : 0.0; });
    const JointEstimate j = estimate_joint(part, no_hand(frames), true, &grip_track, "prismatic");
    ASSERT_EQ(j.from_part.type, "revolute") << reach;
    ASSERT_EQ(j.from_grip.type, "prismatic") << reach;
    EXPECT_EQ(j.type, "prismatic") << reach;
    const Vector3d way = reach > 0.02 ? Vector3d::UnitX() : Vector3d::UnitZ();
    EXPECT_LT(std::acos(std::min(1.0, std::abs(j.axis.dot(way)))), 0.15) << reach;
    EXPECT_EQ(j.press_past_slip, reach < 0.02) << reach;
    EXPECT_EQ(j.source, reach > 0.02 ? "grip" : "part") << reach;
  }
}

TEST(PipelineInfer, AKnobTurnedPastAQuarterTurnIsReadThroughTheGripsHalfTurns) {
  // A nearly flat hand registers about as well turned half a turn about the
  // knob: past an eighth of a turn, half the frames' grip poses come out
  // half a turn off. The knob turned 3 rad and back reads 3 rad, not a
  // twist wrapped into a half turn (twist_unwrap.h).
  const int frames = 150;
  std::mt19937 rng(67);
  std::normal_distribution<double> g(0, 0.0005);
  std::bernoulli_distribution flip(0.5);
  auto angle = [](int f) { return 3.0 * std::sin(kPi * (f - 20) / 110.0); };
  const PartTrack twist = grip(frames, 20, 130, [&](int f) {
    const double a = angle(f) + (std::abs(angle(f)) > kPi / 4 && flip(rng) ? kPi : 0.0);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(a, Vector3d::UnitZ()).toRotationMatrix();
    T.translation() += Vector3d(g(rng), g(rng), g(rng));
    return T;
  });
  std::vector<Vector3d> hand = no_hand(frames);
  for (int f = 20; f < 130; ++f) hand[f] = Vector3d(0, 0, 0.012);
  // The knob's own track slips round its axis (the slip's axis is the
  // joint's, the grip's twist about it the position), or shows nothing
  // (the hand hides the knob: the grip's own hinge and twist); either way
  // the grip's half turns are unwrapped.
  PartTrack hidden = turning(ridged_button(), Vector3d::UnitZ(), Vector3d::Zero(), 0.0, frames, 0.0003, 62);
  with_information(&hidden);
  for (const PartTrack& part : {slipping(frames, 62), hidden}) {
    const JointEstimate knob = estimate_joint(part, hand, true, &twist);
    ASSERT_EQ(knob.source, "grip");
    EXPECT_EQ(knob.type, "revolute");
    ASSERT_EQ(static_cast<int>(knob.q.size()), frames);
    for (int f : {40, 75, 110}) EXPECT_NEAR(std::abs(knob.q[f] - knob.q[10]), std::abs(angle(f)), 0.1) << "frame " << f;
    EXPECT_NEAR(knob.range_hi - knob.range_lo, 3.0, 0.15);
  }
}

TEST(PipelineInfer, AKnobWhoseSlipTurnsItAboutALineBesideItIsReadThroughItsGrip) {
  // A plain round knob (axis z, 6 cm across) whose registration slips by a
  // random walk about a line along its axis 3 cm beside it (seed 1's s0034
  // left knob: its hinge fitted 1.5 cm off, its shape barely showing that
  // turn), held in frames 20 to 130 by a grip twisting it 1.5 rad and
  // back. The slip's hinge runs along the knob's symmetry axis, so it is a
  // slip all the same: the grip gives the position, not the slip.
  const int frames = 150;
  std::mt19937 rng(85);
  std::normal_distribution<double> g(0, 0.0005);
  auto angle = [](int f) { return f < 20 || f >= 130 ? 0.0 : 1.5 * std::sin(kPi * (f - 20) / 110.0); };
  const PartTrack twist = grip(frames, 20, 130, [&](int f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(angle(f), Vector3d::UnitZ()).toRotationMatrix();
    T.translation() += Vector3d(g(rng), g(rng), g(rng));
    return T;
  });
  std::vector<Vector3d> hand = no_hand(frames);
  for (int f = 20; f < 130; ++f) hand[f] = Vector3d(0, 0, 0.012);
  const PartTrack part =
      slipping_round_part(plain_button(), false, false, frames, 87, 0.3, 0.001, Vector3d(0.03, 0, 0));
  const JointEstimate knob = estimate_joint(part, hand, true, &twist, "revolute");
  ASSERT_EQ(knob.from_part.type, "revolute");
  EXPECT_FALSE(turns_about_itself(part.model, knob.from_part.axis, knob.from_part.origin));
  EXPECT_LT(knob.part_visibility, kSlipVisibility);
  EXPECT_EQ(knob.source, "grip");
  EXPECT_EQ(knob.type, "revolute");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(knob.axis.dot(Vector3d::UnitZ())))), 0.1);
  ASSERT_EQ(static_cast<int>(knob.q.size()), frames);
  for (int f : {40, 75, 110}) EXPECT_NEAR(std::abs(knob.q[f] - knob.q[10]), angle(f), 0.15) << "frame " << f;
}

TEST(PipelineInfer, APlainKnobsSlipTooFaintToShowStillGivesItsAxisToItsGrip) {
  // A plain round knob (no ridge: its shape shows no turn about its axis
  // at all, visibility under kMinVisibility) whose registration slips
  // round that axis, held in frames 20 to 130 by fingers twisting it 1.5
  // rad and back while rolling on it: their twist is about an axis 0.5 rad
  // off the knob's (seed 1's s0018 knob: the grip's hinge 1.57 rad off, the
  // part's slip 0.14). The slip's axis is the knob's; the grip gives its
  // position.
  const int frames = 150;
  std::mt19937 rng(91);
  std::normal_distribution<double> g(0, 0.0005);
  const Vector3d rolling(std::sin(0.5), 0, std::cos(0.5));
  auto angle = [](int f) { return f < 20 || f >= 130 ? 0.0 : 1.5 * std::sin(kPi * (f - 20) / 110.0); };
  const PartTrack twist = grip(frames, 20, 130, [&](int f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(angle(f), rolling).toRotationMatrix();
    T.translation() += Vector3d(g(rng), g(rng), g(rng));
    return T;
  });
  std::vector<Vector3d> hand = no_hand(frames);
  for (int f = 20; f < 130; ++f) hand[f] = Vector3d(0, 0, 0.012);
  const PartTrack part = slipping_round_part(plain_button(), false, false, frames, 93, 0.3);
  const JointEstimate knob = estimate_joint(part, hand, true, &twist, "revolute");
  ASSERT_EQ(knob.from_part.type, "revolute");
  EXPECT_LT(knob.part_visibility, kMinVisibility);
  EXPECT_GT(std::acos(std::min(1.0, std::abs(knob.from_grip.axis.normalized().dot(Vector3d::UnitZ())))), 0.3);
  EXPECT_EQ(knob.source, "grip");
  EXPECT_EQ(knob.type, "revolute");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(knob.axis.dot(Vector3d::UnitZ())))), 0.1);
  EXPECT_LT(Eigen::Vector2d(knob.origin.x(), knob.origin.y()).norm(), 0.01);
  EXPECT_GT(knob.range_hi - knob.range_lo, 1.0);
}

// A hidden knob held from frame 20 to 129 and turned 3 rad and back at
// 0.6 rad a frame, twice, from frame `start` (up in 5 frames, held 20, back
// in 5, at rest 25); its grip's registration settles a tenth of the way
// from its last pose each frame (seed 0's s0045: 0.1 rad a frame for 0.9),
// and its grip's points are the hand turned by the true twist plus
// `off(f)`.
struct FastTurnedKnob {
  std::function<double(int)> angle;
  PartTrack twist;  // the grip's registration
  std::vector<Cloud> points;  // the grip's points per frame
  std::vector<Vector3d> hand;
  PartTrack hidden;  // the knob's own track: still
};

FastTurnedKnob fast_turned_knob(int start, unsigned seed, const std::function<double(int)>& off) {
  const int frames = 150;
  FastTurnedKnob k;
  k.angle = [start](int f) {
    if (f < start || f >= 130) return 0.0;
    const int phase = (f - start) % 55;
    return phase < 5 ? 0.6 * phase : phase < 25 ? 3.0 : phase < 30 ? 0.6 * (30 - phase) : 0.0;
  };
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, 0.0005);
  double lagging = 0;
  k.twist = grip(frames, 20, 130, [&](int f) {
    lagging += 0.1 * (k.angle(f) - lagging);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(lagging, Vector3d::UnitZ()).toRotationMatrix();
    T.translation() += Vector3d(g(rng), g(rng), g(rng));
    return T;
  });
  k.points.resize(frames);
  for (int f = 20; f < 130; ++f) {
    k.points[f] = k.twist.model;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(k.angle(f) + off(f), Vector3d::UnitZ()).toRotationMatrix();
    transform_cloud(T, &k.points[f]);
  }
  k.hand = no_hand(frames);
  for (int f = 20; f < 130; ++f) k.hand[f] = Vector3d(0, 0, 0.012);
  k.hidden = turning(ridged_button(), Vector3d::UnitZ(), Vector3d::Zero(), 0.0, frames, 0.0003, seed - 19);
  with_information(&k.hidden);
  return k;
}

TEST(PipelineInfer, AKnobTurnedFasterThanItsGripsRegistrationIsFoundAboutItsHinge) {
  // With the grip's points (the hand turned by the true twist), the twist
  // is searched about the hinge and the knob reads its 3 rad; without them
  // it reads the registration's fraction.
  const FastTurnedKnob k = fast_turned_knob(20, 81, [](int) { return 0.0; });
  const JointEstimate searched = estimate_joint(k.hidden, k.hand, true, &k.twist, "", true, &k.points);
  ASSERT_EQ(searched.source, "grip");
  ASSERT_EQ(searched.type, "revolute");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(searched.axis.dot(Vector3d::UnitZ())))), 0.05);
  for (int f : {22, 30, 47, 60, 77, 85, 102, 115})
    EXPECT_NEAR(std::abs(searched.q[f] - searched.q[10]), k.angle(f), 0.1) << "frame " << f;
  EXPECT_NEAR(searched.range_hi - searched.range_lo, 3.0, 0.15);
  const JointEstimate registered = estimate_joint(k.hidden, k.hand, true, &k.twist);
  ASSERT_EQ(static_cast<int>(registered.q.size()), 150);
  EXPECT_GT(std::abs(std::abs(registered.q[24] - registered.q[10]) - k.angle(24)), 1.0);  // 2.4 rad turned
}

TEST(PipelineInfer, AHeldLeverWhosePosesLagTheHandReadsItsPositionFromItsGrip) {
  // A lever (a 20 cm bar beside the z axis) turned 0.8 rad and back twice
  // by a hand that holds it from frame 20 to 129. Its own registration
  // shows the turn plainly, so its poses give the hinge; but they follow
  // only half of it (a held part's own poses can miss its turn outright:
  // seed 1's s0030 right knob wandered through a radian whether it turned
  // or not, while its grip's twist follows its 3.4 rad turns). The grip's
  // points, the hand turned with the lever, give the whole turn about that
  // hinge; without them the lever reads half its travel.
  const int frames = 150;
  auto angle = [](int f) { return two_strokes(f, 30, 80, 0.8, 8, 15); };
  std::mt19937 rng(91);
  std::normal_distribution<double> g(0, 0.0005);
  PartTrack lever = track_of(box_faces(Vector3d(0.1, 0.01, 0.015), Vector3d(0.1, 0, 0)));
  for (int f = 0; f < frames; ++f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(0.5 * angle(f), Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Vector3d(g(rng), g(rng), g(rng));
    lever.motion.push_back(T);
    lever.tracked.push_back(true);
    lever.rmse.push_back(0.001), lever.inliers.push_back(1), lever.conditioning.push_back(1);
  }
  lever.frames_tracked = frames;
  with_information(&lever);
  // The grip's registration lags as the lever's does; its points do not.
  // The hand holds the lever's end, 15 cm from the hinge.
  PartTrack grip_track = grip(frames, 20, 130, [&](int f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(0.5 * angle(f), Vector3d::UnitZ()).toRotationMatrix();
    return T;
  });
  for (Vector3d& p : grip_track.model.points) p.x() += 0.15;
  std::vector<Cloud> points(frames);
  std::vector<Vector3d> hand = no_hand(frames);
  for (int f = 20; f < 130; ++f) {
    points[f] = grip_track.model;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(angle(f), Vector3d::UnitZ()).toRotationMatrix();
    transform_cloud(T, &points[f]);
    hand[f] = T * Vector3d(0.17, 0, 0.07);
  }
  const JointEstimate held = estimate_joint(lever, hand, true, &grip_track, "", true, &points);
  ASSERT_EQ(held.type, "revolute");
  EXPECT_EQ(held.source, "part");
  EXPECT_TRUE(held.state_from_grip);
  EXPECT_LT(std::acos(std::min(1.0, std::abs(held.axis.dot(Vector3d::UnitZ())))), 0.05);
  ASSERT_EQ(static_cast<int>(held.q.size()), frames);
  for (int f : {10, 34, 45, 60, 95, 140}) EXPECT_NEAR(held.q[f], angle(f), 0.08) << "frame " << f;
  EXPECT_NEAR(held.range_hi - held.range_lo, 0.8, 0.08);
  const JointEstimate unseen = estimate_joint(lever, hand, true, &grip_track);
  ASSERT_EQ(unseen.type, "revolute");
  EXPECT_FALSE(unseen.state_from_grip);
  EXPECT_NEAR(unseen.range_hi - unseen.range_lo, 0.4, 0.08);
}

TEST(PipelineInfer, AGripsFirstAndLastFramesAreReadWithTheFewBesideThem) {
  // The same knob, held still for its first 5 frames, its grip's points
  // turned 0.5 rad off the knob on the grip's first and last frames (the
  // hand arriving and leaving, half seen: seed 1's s0033 power switch,
  // whose first frame read 0.28 rad off and, as q = 0, turned its rest
  // into a press). The knob's rest is still q = 0, before the grip, between
  // the turns and after, and nothing reads below it.
  const FastTurnedKnob k = fast_turned_knob(25, 83, [](int f) { return f == 20 || f == 129 ? 0.5 : 0.0; });
  const JointEstimate knob = estimate_joint(k.hidden, k.hand, true, &k.twist, "", true, &k.points);
  ASSERT_EQ(knob.source, "grip");
  ASSERT_EQ(knob.type, "revolute");
  ASSERT_EQ(static_cast<int>(knob.q.size()), 150);
  for (int f : {10, 22, 27, 35, 65, 90, 120, 140}) EXPECT_NEAR(knob.q[f], k.angle(f), 0.1) << "frame " << f;
  EXPECT_GT(knob.range_lo, -0.1);
}

TEST(PipelineInfer, ARockersGripSwingsAboutItsHingeNotAboutThePartsSlip) {
  // A small part whose registration only slips round an axis through itself
  // (z), pressed by a hand that swings it 0.3 rad about a hinge across it
  // (x, through its base) and back, twice: a rocker. The grip's turn shows
  // plainly about the hinge and not at all about the slip's axis, so the
  // grip's own hinge is the joint, not the slip's axis.
  const int frames = 150;
  std::mt19937 rng(71);
  std::normal_distribution<double> g(0, 0.0005);
  const Vector3d hinge_point(0, 0, -0.005);
  auto swing = [](int f) { return f >= 20 && f < 130 ? 0.3 * std::abs(std::sin(2 * kPi * (f - 20) / 110.0)) : 0.0; };
  const PartTrack rocked = grip(frames, 20, 130, [&](int f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(swing(f), Vector3d::UnitX()).toRotationMatrix();
    T.translation() = hinge_point - T.linear() * hinge_point + Vector3d(g(rng), g(rng), g(rng));
    return T;
  });
  std::vector<Vector3d> hand = no_hand(frames);
  for (int f = 20; f < 130; ++f) hand[f] = Vector3d(0, 0, 0.012);
  const JointEstimate rocker = estimate_joint(slipping(frames, 62), hand, true, &rocked);
  EXPECT_EQ(rocker.source, "grip");
  EXPECT_TRUE(rocker.grip_swings_past_slip);
  EXPECT_EQ(rocker.type, "revolute");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(rocker.axis.dot(Vector3d::UnitX())))), 0.1);
  EXPECT_NEAR(rocker.range_hi - rocker.range_lo, 0.3, 0.05);
  ASSERT_EQ(static_cast<int>(rocker.q.size()), frames);
  EXPECT_NEAR(std::abs(rocker.q[47] - rocker.q[10]), 0.3, 0.05);
  // A knob's grip twists about the slip's axis: the slip's axis stays.
  const PartTrack twisted = grip(frames, 20, 130, [&](int f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(3 * swing(f), Vector3d::UnitZ()).toRotationMatrix();
    T.translation() += Vector3d(g(rng), g(rng), g(rng));
    return T;
  });
  const JointEstimate knob = estimate_joint(slipping(frames, 62), hand, true, &twisted);
  EXPECT_EQ(knob.source, "grip");
  EXPECT_FALSE(knob.grip_swings_past_slip);
  EXPECT_LT(std::acos(std::min(1.0, std::abs(knob.axis.dot(Vector3d::UnitZ())))), 0.1);
}

TEST(PipelineInfer, TheGripAndTheHandsContactsAddTheirEvidence) {
  // A lever turned 1.2 rad about z by a hand 3 cm from its hinge, in frames
  // 20 to 130. Its own track shows nothing; the grip (a few fingertips, their
  // turn barely known) reads the stroke as a slide, a little better than a
  // turn; the hand's contacts plainly trace the arc. Together: a turn.
  const int frames = 150;
  std::mt19937 rng(71);
  std::normal_distribution<double> g(0, 0.001), h(0, 0.002);
  auto angle = [](int f) { return 1.2 * std::sin(kPi * (f - 20) / 110.0); };
  PartTrack slide = grip(frames, 20, 130, [&](int f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Vector3d(0.03 * angle(f) + g(rng), g(rng), g(rng));
    return T;
  });
  for (auto& H : slide.hessian) H.topLeftCorner<3, 3>() *= 1e-4, H.topRightCorner<3, 3>() *= 1e-2, H.bottomLeftCorner<3, 3>() *= 1e-2;
  const PartTrack still = turning(panel(), Vector3d::UnitZ(), Vector3d::Zero(), 0.0, frames, 0.0003, 72);
  std::vector<Vector3d> turning_hand = no_hand(frames), still_hand = no_hand(frames);
  for (int f = 20; f < 130; ++f) {
    turning_hand[f] = Vector3d(0.03 * std::cos(angle(f)) + h(rng), 0.03 * std::sin(angle(f)) + h(rng), 0.02 + h(rng));
    still_hand[f] = Vector3d(0.03 + h(rng), h(rng), 0.02 + h(rng));
  }
  const JointEstimate alone = estimate_joint(still, still_hand, true, &slide);
  ASSERT_EQ(alone.source, "grip");
  EXPECT_EQ(alone.type, "prismatic");
  EXPECT_FALSE(alone.grip_with_hand);
  const JointEstimate both = estimate_joint(still, turning_hand, true, &slide);
  EXPECT_EQ(both.from_grip.type, "prismatic");
  EXPECT_EQ(both.from_hand.type, "revolute");
  EXPECT_EQ(both.source, "grip");
  EXPECT_EQ(both.type.substr(0, 4) == "cont" ? "revolute" : both.type, "revolute");
  EXPECT_TRUE(both.grip_with_hand);
}

TEST(PipelineInfer, TheGripIsTheHandsPointsNearItsContactWhileItHolds) {
  // Hand points in the world frame; the object frame is the world moved
  // 1 m along x. Contacts in frames 1 and 2 only.
  Observations obs;
  obs.times = {0.0, 0.1, 0.2, 0.3};
  Cloud hand;
  for (double x : {0.0, 0.05, 0.09, 0.2, 0.5}) {
    hand.points.push_back(Vector3d(x, 0, 0));
    hand.normals.push_back(Vector3d::UnitZ());
  }
  obs.hand_clouds.assign(4, hand);
  std::vector<Eigen::Isometry3d> to_object(4, Eigen::Isometry3d::Identity());
  for (auto& T : to_object) T.translation() = Vector3d(1, 0, 0);
  std::vector<Vector3d> contacts = no_hand(4);
  contacts[1] = Vector3d(1.0, 0, 0);   // world (0, 0, 0)
  contacts[2] = Vector3d(1.2, 0, 0);   // world (0.2, 0, 0)
  const std::vector<Cloud> g = grip_clouds(obs, contacts, to_object);
  ASSERT_EQ(g.size(), 4u);
  EXPECT_EQ(g[0].size(), 0u);
  EXPECT_EQ(g[3].size(), 0u);
  ASSERT_EQ(g[1].size(), 3u);  // 0, 0.05, 0.09 (within kGripRadius of 0)
  EXPECT_TRUE(g[1].has_normals());
  ASSERT_EQ(g[2].size(), 1u);  // 0.2 alone: 0.09 lies 0.11 from it
  EXPECT_EQ(g[2].points[0], Vector3d(0.2, 0, 0));
  // No hand mask: no grip.
  obs.hand_clouds.clear();
  for (const Cloud& c : grip_clouds(obs, contacts, to_object)) EXPECT_EQ(c.size(), 0u);
}

// A small lever (6 x 1 x 1 cm) at its hinge end on the origin.
Cloud lever() {
  Cloud c;
  for (int i = 0; i <= 30; ++i)
    for (int k = 0; k <= 5; ++k) {
      const double x = 0.06 * i / 30, y = -0.005 + 0.01 * k / 5;
      c.points.push_back(Vector3d(x, y, 0.01)), c.normals.push_back(Vector3d::UnitZ());
      c.points.push_back(Vector3d(x, y, 0.0)), c.normals.push_back(-Vector3d::UnitZ());
      c.points.push_back(Vector3d(x, 0.005, 0.01 * k / 5)), c.normals.push_back(Vector3d::UnitY());
      c.points.push_back(Vector3d(x, -0.005, 0.01 * k / 5)), c.normals.push_back(-Vector3d::UnitY());
    }
  return c;
}

// Two presses of 0.35 rad about y through the origin, each ramping up over
// 8 frames, held 6, and back; rest elsewhere.
double press(int f) { return two_strokes(f, 40, 90, 0.35, 8, 6); }

TEST(PipelineInfer, ALeversPressShowsThroughRegistrationNoiseAndFlips) {
  // Registration of a small part: 2 degrees of rotation noise per frame,
  // 1 mm of position noise, and one frame in seven flipped end over end (the
  // lever's mirror image fits its points about as well).
  const int frames = 140;
  PartTrack t = track_of(lever());
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0, 1);
  const Vector3d centre(0.03, 0, 0.005);
  std::vector<bool> flipped(frames, false);
  for (int f = 0; f < frames; ++f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(press(f), Vector3d::UnitY()).toRotationMatrix() *
                 Eigen::AngleAxisd(0.035, Vector3d(g(rng), g(rng), g(rng)).normalized()).toRotationMatrix();
    if (f % 7 == 3) {
      flipped[f] = true;
      const Eigen::Matrix3d flip = Eigen::AngleAxisd(kPi, Vector3d::UnitZ()).toRotationMatrix();
      T.linear() = T.linear() * flip;
      T.translation() = centre - T.linear() * centre;  // end over end about its middle
    }
    T.translation() += 0.001 * Vector3d(g(rng), g(rng), g(rng));
    t.motion.push_back(T);
    t.tracked.push_back(true);
    t.rmse.push_back(0.001), t.inliers.push_back(0.8), t.conditioning.push_back(1);
  }
  t.frames_tracked = frames;
  // The flipped frames are dropped; the rest averaged in runs of frames.
  std::vector<std::vector<int>> frames_of_sample;
  const Track samples = part_samples(t, centre, 5, &frames_of_sample);
  ASSERT_EQ(samples.size(), frames_of_sample.size());
  EXPECT_LT(samples.size(), static_cast<size_t>(frames / 3));
  int kept = 0;
  for (const std::vector<int>& fs : frames_of_sample)
    for (int f : fs) {
      EXPECT_FALSE(flipped[f]) << "frame " << f;
      ++kept;
    }
  EXPECT_GT(kept, frames * 3 / 4);
  const JointEstimate j = estimate_joint(t, no_hand(frames));
  ASSERT_EQ(j.type, "revolute");
  EXPECT_EQ(j.source, "part");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(j.axis.dot(Vector3d::UnitY())))), 0.15);
  EXPECT_NEAR(j.range_hi - j.range_lo, 0.35, 0.1);
}

// A lever pressed about y (press()) whose registration also turns about its
// bar (x) by half the swing, with 0.01 rad and 0.5 mm of noise.
PartTrack tilting_lever(int frames, std::mt19937& rng) {
  std::normal_distribution<double> g(0, 1);
  PartTrack t = track_of(lever());
  for (int f = 0; f < frames; ++f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(press(f), Vector3d::UnitY()).toRotationMatrix() *
                 Eigen::AngleAxisd(0.5 * press(f), Vector3d::UnitX()).toRotationMatrix() *
                 Eigen::AngleAxisd(0.01, Vector3d(g(rng), g(rng), g(rng)).normalized()).toRotationMatrix();
    T.translation() = 0.0005 * Vector3d(g(rng), g(rng), g(rng));
    t.motion.push_back(T);
    t.tracked.push_back(true);
    t.rmse.push_back(0.001), t.inliers.push_back(1), t.conditioning.push_back(1);
  }
  t.frames_tracked = frames;
  with_information(&t);
  return t;
}

TEST(PipelineInfer, AHeldLeversHingeIsTheGripsWhereItsOwnRegistrationTilts) {
  // A lever's bar is nearly round about its length, and its registration
  // turns about that length as the lever swings (here by half the swing):
  // the hinge its poses fit tilts 27 degrees. The hand holding it turns
  // with it about the true hinge (y), and its grip shows that plainly.
  const int frames = 140;
  std::mt19937 rng(73);
  std::normal_distribution<double> g(0, 1);
  PartTrack t = tilting_lever(frames, rng);
  const PartTrack held = grip(frames, 20, 130, [&](int f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(press(f), Vector3d::UnitY()).toRotationMatrix();
    T.translation() = 0.0005 * Vector3d(g(rng), g(rng), g(rng));
    return T;
  });
  std::vector<Vector3d> hand = no_hand(frames);
  for (int f = 20; f < 130; ++f) hand[f] = Vector3d(0.05, 0, 0.012);
  auto off_y = [](const JointEstimate& j) { return std::acos(std::min(1.0, std::abs(j.axis.dot(Vector3d::UnitY())))); };
  // Alone, the part's tilted hinge.
  const JointEstimate alone = estimate_joint(t, hand, true, nullptr);
  ASSERT_EQ(alone.type, "revolute");
  EXPECT_GT(off_y(alone), 0.3);
  const JointEstimate lever = estimate_joint(t, hand, true, &held);
  ASSERT_EQ(lever.type, "revolute");
  EXPECT_EQ(lever.source, "part");
  EXPECT_TRUE(lever.hinge_from_grip);
  EXPECT_LT(off_y(lever), 0.05);
  EXPECT_LT(Eigen::Vector2d(lever.origin.x(), lever.origin.z()).norm(), 0.01);
  EXPECT_NEAR(lever.range_hi - lever.range_lo, 0.35, 0.05);
  ASSERT_EQ(static_cast<int>(lever.q.size()), frames);
  EXPECT_NEAR(std::abs(lever.q[50] - lever.q[30]), 0.35, 0.05);
}

TEST(PipelineInfer, AGripsRegistrationSpunForOneBinDoesNotHideItsHinge) {
  // The held lever above, its grip's registration spun 0.9 rad about the
  // hand's own long axis (z through the grip) for frames 25 to 29, at rest:
  // one bin of the typing track, consecutive, so no spike. Kept, it costs
  // every hinge more than it costs no motion; the grip's track is typed
  // without its worst sample, and its hinge is the lever's.
  const int frames = 140;
  std::mt19937 rng(79);
  std::normal_distribution<double> g(0, 1);
  PartTrack t = tilting_lever(frames, rng);
  const Vector3d grip_centre(0.02, 0, 0.06);
  const PartTrack held = grip(frames, 20, 130, [&](int f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(press(f), Vector3d::UnitY()).toRotationMatrix();
    if (f >= 25 && f < 30) {
      T.linear() = Eigen::AngleAxisd(0.9, Vector3d::UnitZ()).toRotationMatrix();
      T.translation() = grip_centre - T.linear() * grip_centre;
    }
    T.translation() += 0.0005 * Vector3d(g(rng), g(rng), g(rng));
    return T;
  });
  std::vector<Vector3d> hand = no_hand(frames);
  for (int f = 20; f < 130; ++f) hand[f] = Vector3d(0.05, 0, 0.012);
  const JointEstimate lever = estimate_joint(t, hand, true, &held);
  ASSERT_EQ(lever.from_grip.type, "revolute");
  // The spun frames' sample (its bin as the spike test left it).
  int spun_left_out = 0;
  for (int f : lever.grip_frames_left_out) spun_left_out += f >= 25 && f < 30;
  EXPECT_GE(spun_left_out, 4);
  EXPECT_LE(lever.grip_frames_left_out.size(), 5u);
  ASSERT_EQ(lever.type, "revolute");
  EXPECT_TRUE(lever.hinge_from_grip);
  EXPECT_LT(std::acos(std::min(1.0, std::abs(lever.axis.dot(Vector3d::UnitY())))), 0.05);
}

TEST(PipelineInfer, ADoorSnappedOpenForAFewFramesIsAMotionNotASpike) {
  // A door a function snaps open by 60 degrees in three frames, holds open
  // for five and shuts in three, twice; one frame at rest is flipped about
  // the door's middle (a registration failure). The open frames are each
  // far from their neighbourhood's median, but between their neighbours,
  // and the door's centroid swings with them.
  const int frames = 90;
  auto open = [](int f) {
    for (int start : {20, 55}) {
      const int k = f - start;
      if (k >= 0 && k < 3) return (k + 1) / 3.0;
      if (k >= 3 && k < 8) return 1.0;
      if (k >= 8 && k < 11) return (10 - k) / 3.0;
    }
    return 0.0;
  };
  PartTrack t = track_of(panel());
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0, 0.001);
  const int flipped = 45;
  for (int f = 0; f < frames; ++f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(open(f) * kPi / 3, Vector3d::UnitZ()).toRotationMatrix();
    if (f == flipped) {
      T.linear() = Eigen::AngleAxisd(kPi, Vector3d::UnitX()).toRotationMatrix();
      T.translation() = Vector3d(0.3, 0, 0.4) - T.linear() * Vector3d(0.3, 0, 0.4);
    }
    T.translation() += Vector3d(g(rng), g(rng), g(rng));
    t.motion.push_back(T);
    t.tracked.push_back(true);
    t.rmse.push_back(0.001), t.inliers.push_back(0.9), t.conditioning.push_back(1);
  }
  t.frames_tracked = frames;
  std::vector<std::vector<int>> frames_of_sample;
  part_samples(t, centroid(t.model), 1, &frames_of_sample);
  std::set<int> kept;
  for (const std::vector<int>& fs : frames_of_sample) kept.insert(fs.begin(), fs.end());
  EXPECT_EQ(kept.count(flipped), 0u);
  // Only frames at a corner of the motion (where it starts or stops) may go.
  int open_frames = 0, open_kept = 0;
  for (int f = 0; f < frames; ++f)
    if (open(f) > 0) ++open_frames, open_kept += static_cast<int>(kept.count(f));
  EXPECT_GE(open_kept, open_frames - 8);
  const JointEstimate j = estimate_joint(t, no_hand(frames), false);
  ASSERT_EQ(j.type, "revolute");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(j.axis.dot(Vector3d::UnitZ())))), 0.02);
  EXPECT_NEAR(j.range_hi - j.range_lo, kPi / 3, 0.05);
}

TEST(PipelineInfer, AGraspHoldsOnWhileThePartsRegistrationFails) {
  // A lever at rest in frames 0-19 and 40-59, registered there; lifted by
  // the hand in frames 20-39, where its registration failed (hidden under
  // the hand). The hand holds its tip all along, then draws back 10 cm.
  const int frames = 70;
  PartTrack t = track_of(lever());
  for (int f = 0; f < frames; ++f) {
    t.motion.push_back(Eigen::Isometry3d::Identity());
    t.tracked.push_back(f < 20 || f >= 40);
    t.rmse.push_back(0.001), t.inliers.push_back(0.8), t.conditioning.push_back(1);
  }
  std::vector<Vector3d> hand = no_hand(frames);
  for (int f = 10; f < 60; ++f) {
    const double q = f >= 20 && f < 40 ? 1.0 * std::sin(kPi * (f - 20) / 20.0) : 0.0;
    hand[f] = Eigen::AngleAxisd(-q, Vector3d::UnitY()) * Vector3d(0.055, 0, 0.015);
  }
  for (int f = 60; f < frames; ++f) hand[f] = Vector3d(0.055, 0, 0.015 + 0.01 * (f - 59));
  // A second part far away never gets the hand; a static part has no track.
  PartTrack far = t;
  for (Vector3d& p : far.model.points) p += Vector3d(1, 0, 0);
  const std::vector<std::vector<Vector3d>> held = assign_hand_contacts(hand, {&t, nullptr, &far});
  ASSERT_EQ(held.size(), 3u);
  for (int f = 10; f < 60; ++f) EXPECT_TRUE(held[0][f].allFinite()) << "frame " << f;
  // The retreat starts at rest (registered): beyond 3 cm it is not a contact.
  for (int f = 63; f < frames; ++f) EXPECT_FALSE(held[0][f].allFinite()) << "frame " << f;
  for (int f = 0; f < frames; ++f) EXPECT_FALSE(held[1][f].allFinite() || held[2][f].allFinite());
}

// The hand touches receptors; effectors and object parts move because a
// function drives them (or not at all): their contacts are dropped, after
// each contact went to its nearest part. Without receptor roles, all stay.
TEST(PipelineInfer, OnlyReceptorsKeepTheHandsContacts) {
  const Vector3d p(0.1, 0.2, 0.3);
  const std::vector<std::vector<Vector3d>> contacts(5, std::vector<Vector3d>(3, p));
  auto kept = contacts;
  keep_receptor_contacts({"object", "receptor", "effector", "receptor+effector", "receptor"}, &kept);
  for (int f = 0; f < 3; ++f) {
    EXPECT_FALSE(kept[0][f].allFinite());
    EXPECT_TRUE(kept[1][f].isApprox(p));
    EXPECT_FALSE(kept[2][f].allFinite());
    EXPECT_FALSE(kept[3][f].allFinite());
    EXPECT_TRUE(kept[4][f].isApprox(p));
  }
  kept = contacts;
  keep_receptor_contacts({"object", "handle", "spout", "lid", "knob"}, &kept);
  for (const auto& part : kept)
    for (const Vector3d& q : part) EXPECT_TRUE(q.isApprox(p));
}

TEST(PipelineInfer, JointMotionTurnsAboutTheAxisLine) {
  JointEstimate j;
  j.type = "revolute";
  j.axis = Vector3d::UnitZ();
  j.origin = Vector3d(1, 0, 0);
  const Vector3d p = joint_motion(j, kPi / 2) * Vector3d(2, 0, 0);
  EXPECT_TRUE(p.isApprox(Vector3d(1, 1, 0), 1e-12)) << p.transpose();
  j.type = "prismatic";
  EXPECT_TRUE((joint_motion(j, 0.1) * Vector3d::Zero()).isApprox(Vector3d(0, 0, 0.1), 1e-12));
}

TEST(PipelineInfer, MeanTransformAndSpecNames) {
  Eigen::Isometry3d a = Eigen::Isometry3d::Identity(), b = a;
  a.linear() = Eigen::AngleAxisd(0.2, Vector3d::UnitZ()).toRotationMatrix();
  a.translation() = Vector3d(1, 0, 0);
  b.linear() = Eigen::AngleAxisd(-0.2, Vector3d::UnitZ()).toRotationMatrix();
  b.translation() = Vector3d(-1, 2, 0);
  const Eigen::Isometry3d m = mean_transform({a, b});
  EXPECT_TRUE(m.linear().isApprox(Eigen::Matrix3d::Identity(), 1e-9));
  EXPECT_TRUE(m.translation().isApprox(Vector3d(0, 1, 0), 1e-12));
  EXPECT_EQ(spec_name("lid button"), "lid_button");
  EXPECT_EQ(spec_name("3d"), "_3d");
  EXPECT_EQ(spec_name(""), "_");
  EXPECT_EQ(spec_name("a\"); import os #"), "a____import_os__");
  EXPECT_EQ(spec_name(std::string(100, 'x')).size(), 64u);
}

}  // namespace

// The round knob once more, its rim held and turned by a fraction of a
// radian, the hand's contacts seen with 8 mm noise: over so short an arc
// the noise makes a slide about as likely as the turn. (`radius` and
// `noise` for a fingertip rolling round a small circle over a button.)
std::vector<Vector3d> rim_held(int frames, double sweep, unsigned seed, double radius = 0.06, double noise = 0.008) {
  std::vector<Vector3d> hand = no_hand(frames);
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, noise);
  for (int f = 20; f < 100; ++f) {
    const double q = sweep * (f - 20) / 79.0;
    hand[f] = Vector3d(radius * std::cos(q), radius * std::sin(q), 0.02) + Vector3d(g(rng), g(rng), g(rng));
  }
  return hand;
}

// The round knob turned 1.2 rad by its rim, its registration slipping
// about its own axis by a few degrees and tilting by a fraction of one (a
// round part's registration noise runs along the turn its shape cannot
// show). The hand's contacts alone show the turn, but their arc of a few
// centimetres under 8 mm of noise leaves its axis loose; the part's own
// track, fitted with a hinge, holds it (axis_from_part), and the contacts
// along it give the position.
TEST(PipelineInfer, TheHandsContactsSayHowFarThePartsTrackAboutWhat) {
  const int frames = 120;
  PartTrack t = turning(ring(0.03, 0.02), Vector3d::UnitZ(), Vector3d::Zero(), 0.0, frames, 0.0005, 4);
  std::mt19937 rng(21);
  std::normal_distribution<double> slip(0, 0.05), tilt(0, 0.003);
  for (Eigen::Isometry3d& m : t.motion)
    m.linear() = (Eigen::AngleAxisd(slip(rng), Vector3d::UnitZ()) * Eigen::AngleAxisd(tilt(rng), Vector3d::UnitX()) *
                  Eigen::AngleAxisd(tilt(rng), Vector3d::UnitY()))
                     .toRotationMatrix();
  const std::vector<Vector3d> hand = rim_held(frames, 1.2, 8);
  const JointEstimate j = estimate_joint(t, hand, true, nullptr, "revolute");
  ASSERT_EQ(j.from_part.type, "fixed");  // the slip shows no motion
  EXPECT_TRUE(j.axis_from_part);
  EXPECT_EQ(j.source, "hand");
  EXPECT_NE(j.type, "prismatic");
  auto off_z = [](const Vector3d& a) { return std::acos(std::min(1.0, std::abs(a.normalized().dot(Vector3d::UnitZ())))); };
  EXPECT_LT(off_z(j.axis), 0.05);
  Track contacts;  // the contacts' own hinge is looser
  for (const Vector3d& h : hand)
    if (!std::isnan(h.x())) contacts.positions.push_back(h);
  EXPECT_GT(off_z(estimate_articulation_as(contacts, "revolute").axis), 2 * off_z(j.axis));
  EXPECT_NEAR(j.range_hi - j.range_lo, 1.2, 0.25);  // how far: the contacts'
}

// A function whose effector was never seen keeps its template: the
// effector stands in as a sphere fixed to the root (once, however many
// functions it serves), and the spec checks. A geometry effect needs the
// effector's own motion: left out; so is an effector that was not merely
// unseen but is not a part at all.
TEST(PipelineInfer, AnUnseenEffectorStandsInAsASphere) {
  namespace fs = std::filesystem;
  std::vector<AssembledPart> parts(2);
  parts[0].name = "body", parts[0].role = "object", parts[0].root = true, parts[0].mesh = "meshes/body.obj";
  parts[1].name = "switch", parts[1].role = "receptor", parts[1].mesh = "meshes/switch.obj", parts[1].parent = "body";
  parts[1].joint.type = "prismatic";
  parts[1].joint.axis = Vector3d::UnitX();
  parts[1].joint.range_hi = 0.01;
  auto function = [](const std::string& name, const std::string& effector, const std::string& effect) {
    InferredFunction f;
    f.name = name, f.receptor = "switch", f.effector = effector;
    f.mapping = {{"type", "binary"}, {"threshold", 0.005}};
    f.effect = {{"type", effect}, {"range", {0.0, effect == "geometry" ? 0.5 : 800.0}}};
    return f;
  };
  const std::vector<InferredFunction> functions = {function("light", "bulb", "illumination"),
                                                   function("warm", "bulb", "temperature"),
                                                   function("lift", "ram", "geometry"),
                                                   function("glow", "nowhere", "illumination")};
  StandIns unseen;
  unseen.names = {"bulb", "ram"};
  unseen.centre = Vector3d(0.1, 0.2, 0.3);
  efc::Diagnostics diags;
  const nlohmann::ordered_json spec =
      assemble_spec("lamp", "", parts, functions, unseen, Eigen::Isometry3d::Identity(), "meta.json", diags);

  ASSERT_EQ(spec["parts"].size(), 3u);
  const auto& bulb = spec["parts"][2];
  EXPECT_EQ(bulb["name"], "bulb");
  EXPECT_EQ(bulb["geometry"]["sphere"]["radius"], kStandInRadius);
  EXPECT_EQ(bulb["geometry"]["sphere"]["center"], nlohmann::ordered_json::array({0.1, 0.2, 0.3}));
  EXPECT_EQ(bulb["joint"]["type"], "fixed");
  EXPECT_EQ(bulb["joint"]["parent"], "body");
  ASSERT_EQ(spec["functions"].size(), 2u);
  EXPECT_EQ(spec["functions"][0]["name"], "light");
  EXPECT_EQ(spec["functions"][1]["name"], "warm");
  int stand_ins = 0, left_out = 0;
  for (const efc::Diagnostic& d : diags.items()) stand_ins += d.code == "E1066", left_out += d.code == "E1055";
  EXPECT_EQ(stand_ins, 1);
  EXPECT_EQ(left_out, 2);  // lift (geometry) and glow (no such part)

  // It checks as efc check would (the meshes two small tetrahedra).
  const fs::path dir = fs::temp_directory_path() / ("efc-stand-in-" + std::to_string(::getpid()));
  fs::create_directories(dir / "meshes");
  for (const char* mesh : {"body", "switch"}) {
    std::ofstream obj(dir / "meshes" / (std::string(mesh) + ".obj"));
    obj << "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  }
  std::ofstream(dir / "spec.json") << spec.dump(2);
  efc::Diagnostics check;
  EXPECT_TRUE(efc::load_spec((dir / "spec.json").string(), efc::LoadOptions{}, check).has_value());
  for (const efc::Diagnostic& d : check.items())
    EXPECT_NE(d.severity, efc::Severity::Error) << d.code << " " << d.message;
  fs::remove_all(dir);
}

// A button pressed a few millimetres: its own track (registered on hundreds
// of points) shows it staying put, and the hand's contacts, a fingertip
// rolling round a circle of 6 mm as it pressed (seed 0's s0030: 4 mm), fit
// a hinge far better than a slide. That turn is the hand's, within twice
// its detector's error of where it began: the name types the part, as
// where no track shows a motion at all.
TEST(PipelineInfer, AHandsMotionWithinItsNoiseOverAStillPartIsTypedByThePartsName) {
  const int frames = 120;
  const PartTrack t = turning(ring(0.03, 0.02), Vector3d::UnitZ(), Vector3d::Zero(), 0.0, frames, 0.0005, 4);
  const std::vector<Vector3d> hand = rim_held(frames, 6.0, 3, 0.006, 0.002);
  const JointEstimate unnamed = estimate_joint(t, hand);
  ASSERT_EQ(unnamed.source, "hand");
  ASSERT_EQ(unnamed.type, "revolute");
  ASSERT_GT(unnamed.from_hand.p_revolute, kNamePriorOdds * unnamed.from_hand.p_prismatic);
  EXPECT_TRUE(unnamed.motion_untyped);
  EXPECT_FALSE(unnamed.type_from_name);
  const JointEstimate button = estimate_joint(t, hand, true, nullptr, "prismatic");
  EXPECT_EQ(button.type, "prismatic");
  EXPECT_TRUE(button.motion_untyped);
  EXPECT_TRUE(button.type_from_name);
  EXPECT_LE(button.confidence, 0.5);
  // A part nobody operates is not typed by a hand.
  EXPECT_FALSE(estimate_joint(t, hand, false, nullptr, "prismatic").motion_untyped);
  // Nor does a button too small to register (80 points) change that: the
  // contacts' few millimetres are theirs whatever its track says.
  PartTrack small = t;
  small.model.points.resize(80);
  small.model.normals.resize(80);
  const JointEstimate tiny = estimate_joint(small, hand, true, nullptr, "prismatic");
  EXPECT_TRUE(tiny.motion_untyped);
  EXPECT_EQ(tiny.type, "prismatic");
  // The hand's contacts going round a 3 cm circle show their turn: the
  // name's prior weighs against the likelihoods as before.
  std::vector<Vector3d> wide = hand;
  for (int f = 20; f < 100; ++f) wide[f] = 5.0 * (hand[f] - Vector3d(0, 0, 0.02)) + Vector3d(0, 0, 0.02);
  const JointEstimate lever = estimate_joint(t, wide, true, nullptr, "prismatic");
  EXPECT_FALSE(lever.motion_untyped);
  EXPECT_EQ(lever.type, "revolute");
}

// Contacts going 3.7 cm round a hinge 2 cm beside a square button whose
// own track, 486 points, shows it still: a turn about that hinge would
// show plainly on the button's faces, so the motion was the hand's, not
// the button's (seed 0's s0058 speed button: its contacts' turn of 2.4 rad
// at 2 cm, visibility 0.93 on its shape, read as a hinge at 26 to 1). Its
// name types it. The round knob above, turned about its own axis by the
// same kind of contacts, shows nothing on its shape and stays a hinge.
TEST(PipelineInfer, AHandsTurnAStillPartsShapeWouldShowIsTheHandsAlone) {
  const int frames = 120;
  const PartTrack t =
      turning(box_faces(Vector3d(0.01, 0.01, 0.006), Vector3d(0, 0, 0.006)), Vector3d::UnitZ(), Vector3d::Zero(), 0.0,
              frames, 0.0005, 4);
  std::vector<Vector3d> hand = rim_held(frames, 2.4, 5, 0.02, 0.002);
  for (Vector3d& h : hand)
    if (h.allFinite()) h += Vector3d(-0.02, 0, 0);  // the circle through the button, its centre beside it
  const JointEstimate unnamed = estimate_joint(t, hand);
  ASSERT_EQ(unnamed.source, "hand");
  ASSERT_EQ(unnamed.type, "revolute");
  ASSERT_GT(unnamed.from_hand.radius, 0.015);
  ASSERT_GT(unnamed.from_hand.p_revolute, kNamePriorOdds * unnamed.from_hand.p_prismatic);
  EXPECT_GE(unnamed.hand_motion_visibility, kSlipVisibility);
  EXPECT_TRUE(unnamed.motion_untyped);
  const JointEstimate button = estimate_joint(t, hand, true, nullptr, "prismatic");
  EXPECT_EQ(button.type, "prismatic");
  EXPECT_TRUE(button.type_from_name);
  EXPECT_LE(button.confidence, 0.5);
  // The button seen from the front alone (its face: a turn about the
  // face's normal does not show on it), the contacts turning about an
  // upright axis across that normal: the same.
  Cloud face;
  const Cloud box = box_faces(Vector3d(0.01, 0.006, 0.01), Vector3d(0, 0.006, 0));
  for (size_t i = 0; i < box.size(); ++i)
    if (box.normals[i].y() < -0.5) face.points.push_back(box.points[i]), face.normals.push_back(box.normals[i]);
  Cloud front = face;  // enough points to register: the face sampled finer
  for (int k = 1; k < 4; ++k)
    for (size_t i = 0; i < face.size(); ++i)
      front.points.push_back(face.points[i] + Vector3d(0.0005 * k, 0, 0.0005 * k)), front.normals.push_back(face.normals[i]);
  const PartTrack seen_from_front = turning(front, Vector3d::UnitZ(), Vector3d::Zero(), 0.0, frames, 0.0005, 4);
  Vector3d symmetry;
  ASSERT_TRUE(near_symmetry_axis(seen_from_front.model, &symmetry));
  ASSERT_GT(std::abs(symmetry.y()), 0.9);
  const JointEstimate front_button = estimate_joint(seen_from_front, hand, true, nullptr, "prismatic");
  EXPECT_TRUE(front_button.motion_untyped);
  EXPECT_EQ(front_button.type, "prismatic");
  // A ring turned about its own axis by such contacts: nothing on its
  // shape would show it, and the hand's turn is the part's.
  const PartTrack round = turning(ring(0.03, 0.02), Vector3d::UnitZ(), Vector3d::Zero(), 0.0, frames, 0.0005, 4);
  const JointEstimate knob = estimate_joint(round, rim_held(frames, 2.4, 5, 0.03, 0.002), true, nullptr, "prismatic");
  EXPECT_LT(knob.hand_motion_visibility, kSlipVisibility);
  EXPECT_FALSE(knob.motion_untyped);
  EXPECT_EQ(knob.type, "revolute");
}

TEST(PipelineInfer, ANameSettlesANearTieAndNothingMore) {
  const int frames = 120;
  const PartTrack t = turning(ring(0.03, 0.02), Vector3d::UnitZ(), Vector3d::Zero(), 0.0, frames, 0.0005, 4);
  // Turned 0.4 rad: the hand's contacts favour a slide by less than the
  // name's kNamePriorOdds, four to one (these seeds' odds: 1.5 to 1; 10 to 1 below).
  const std::vector<Vector3d> tie = rim_held(frames, 0.4, 11);
  const JointEstimate unnamed = estimate_joint(t, tie);
  ASSERT_EQ(unnamed.source, "hand");
  ASSERT_EQ(unnamed.type, "prismatic");
  ASSERT_GT(unnamed.from_hand.p_prismatic, unnamed.from_hand.p_revolute);
  ASSERT_LT(unnamed.from_hand.p_prismatic, kNamePriorOdds * unnamed.from_hand.p_revolute);
  const JointEstimate knob = estimate_joint(t, tie, true, nullptr, "revolute");
  EXPECT_EQ(knob.type, "revolute");
  EXPECT_TRUE(knob.type_from_name);
  EXPECT_FALSE(knob.assumed_moving);
  EXPECT_EQ(knob.source, "hand");
  EXPECT_LT(std::acos(std::min(1.0, std::abs(knob.axis.dot(Vector3d::UnitZ())))), 0.5);
  // The posterior with the prior: 4 p_rev / (4 p_rev + p_pri).
  const double p = kNamePriorOdds * unnamed.from_hand.p_revolute;
  EXPECT_NEAR(knob.confidence, p / (p + unnamed.from_hand.p_prismatic), 1e-9);
  // The name agreeing changes nothing but the flag's absence.
  const JointEstimate slide = estimate_joint(t, tie, true, nullptr, "prismatic");
  EXPECT_EQ(slide.type, "prismatic");
  EXPECT_FALSE(slide.type_from_name);
  // Turned 0.5 rad with other noise: ten to one for the slide. The name
  // does not outweigh that.
  const std::vector<Vector3d> plain = rim_held(frames, 0.5, 3);
  const JointEstimate plain_unnamed = estimate_joint(t, plain);
  ASSERT_EQ(plain_unnamed.type, "prismatic");
  ASSERT_GT(plain_unnamed.from_hand.p_prismatic, kNamePriorOdds * plain_unnamed.from_hand.p_revolute);
  const JointEstimate plain_knob = estimate_joint(t, plain, true, nullptr, "revolute");
  EXPECT_EQ(plain_knob.type, "prismatic");
  EXPECT_FALSE(plain_knob.type_from_name);
}
