// The articulation estimator on pose tracks that carry their registration's
// information (weighted_fits.h): noise along a direction the part's shape
// does not constrain (a round button's spin, a plate's slide in its own
// plane) is not motion, while real hinges and slides are still found. Each
// case is also run without the information, where the same noise wins: the
// weighting is what makes the difference.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pipeline/articulation/articulation.h"

namespace efc::pipeline {
namespace {

using Eigen::Vector3d;
using Mat6 = Eigen::Matrix<double, 6, 6>;

constexpr double kPi = 3.14159265358979323846;

// Information of a pose known to sigma_rot (rad) and sigma_pos (m) in every
// direction but the unconstrained ones given (a rotation axis, translation
// directions), which get almost none.
Mat6 information(double sigma_rot, double sigma_pos, const std::vector<Vector3d>& free_rotations,
                 const std::vector<Vector3d>& free_translations) {
  Mat6 W = Mat6::Zero();
  Eigen::Matrix3d rot = Eigen::Matrix3d::Identity() / (sigma_rot * sigma_rot);
  Eigen::Matrix3d pos = Eigen::Matrix3d::Identity() / (sigma_pos * sigma_pos);
  for (const Vector3d& a : free_rotations) rot -= (1 / (sigma_rot * sigma_rot)) * a * a.transpose();
  for (const Vector3d& d : free_translations) pos -= (1 / (sigma_pos * sigma_pos)) * d * d.transpose();
  W.block<3, 3>(0, 0) = rot + 1e-6 * Eigen::Matrix3d::Identity();
  W.block<3, 3>(3, 3) = pos + 1e-6 * Eigen::Matrix3d::Identity();
  return W;
}

Track without_information(Track t) {
  t.information.clear();
  return t;
}

double axis_error(const Vector3d& a, const Vector3d& b) {
  return std::acos(std::min(1.0, std::fabs(a.normalized().dot(b.normalized()))));
}

// A round plunger pushed 3 cm along -y and back, three times; the tracker
// spins it about its own axis at random (a random walk of ~10 degrees a
// sample), which its shape cannot show.
TEST(WeightedArticulation, ARoundPlungerThatSpinsIsASlide) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 1);
  const Vector3d axis(0, -1, 0), centre(0.1, -0.2, 0.5);
  Track t;
  double spin = 0;
  const int n = 30;
  for (int i = 0; i < n; ++i) {
    const double press = 0.03 * std::pow(std::sin(3 * kPi * i / (n - 1)), 2);
    spin += 0.17 * noise(rng);
    t.positions.push_back(centre + press * axis + 0.001 * Vector3d(noise(rng), noise(rng), noise(rng)));
    t.rotations.emplace_back(Eigen::AngleAxisd(spin, axis) *
                             Eigen::AngleAxisd(0.005 * noise(rng), Vector3d(noise(rng), noise(rng), noise(rng)).normalized()));
    t.information.push_back(information(0.005, 0.001, {axis}, {}));
  }
  const Articulation weighted = estimate_articulation(t);
  EXPECT_EQ(weighted.type, "prismatic") << articulation_json(weighted);
  EXPECT_LT(axis_error(weighted.axis, axis), 0.1) << articulation_json(weighted);
  EXPECT_NEAR(weighted.range_hi - weighted.range_lo, 0.03, 0.004) << articulation_json(weighted);
  // Unweighted, the spin is the largest motion in the track.
  EXPECT_EQ(estimate_articulation(without_information(t)).type, "revolute");
}

// A fixed plate (normal z) that the tracker lets slide 2 cm in its own plane
// and turn about its normal: nothing its shape shows moves.
// A round button whose registration slips round its own axis by a random
// walk, and whose information does not say so (the shape held the spin a
// little, and the tracker took the slip for motion): the hinge about that
// axis wins the typing. Pressed 8 mm along the axis in a few samples, the
// same hinge sliding along its axis explains the track better, and the
// slide is the press; a knob that only turns gains nothing from a slide.
TEST(WeightedArticulation, AHingeThatAlsoSlidesShowsTheButtonsPress) {
  const Vector3d axis(0, -1, 0), centre(0.1, -0.2, 0.5);
  auto track = [&](bool pressed, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, 1);
    Track t;
    double spin = 0;
    for (int i = 0; i < 30; ++i) {
      const double press = pressed && (i % 10 >= 6 && i % 10 <= 7) ? 0.008 : 0.0;
      spin += 0.15 * noise(rng);
      const Eigen::AngleAxisd turn(spin, axis);
      t.positions.push_back(centre + press * axis + 0.0005 * Vector3d(noise(rng), noise(rng), noise(rng)));
      t.rotations.emplace_back(turn * Eigen::AngleAxisd(0.005 * noise(rng), Vector3d(noise(rng), noise(rng), noise(rng)).normalized()));
      t.information.push_back(information(0.005, 0.001, {}, {}));
    }
    return t;
  };
  const Articulation button = estimate_articulation(track(true, 21));
  ASSERT_EQ(button.type, "revolute") << articulation_json(button);
  EXPECT_LT(button.slide_bic, button.revolute.bic);
  EXPECT_LT(axis_error(button.slide_axis, axis), 0.1);
  ASSERT_EQ(button.slide.size(), 30u);
  for (int i = 0; i < 30; ++i) {
    const double press = (i % 10 >= 6 && i % 10 <= 7) ? 0.008 : 0.0;
    EXPECT_NEAR(std::abs(button.slide[i]), press, 0.0035) << "sample " << i;
  }
  const Articulation knob = estimate_articulation(track(false, 22));
  ASSERT_EQ(knob.type, "revolute") << articulation_json(knob);
  EXPECT_GE(knob.slide_bic, knob.revolute.bic);
}

// The same button, but its registration also slips across its face by a
// centimetre or more (a flat disc shows that only on its thin rim, yet the
// information claims a millimetre): the hinge's noise scale, over all six
// directions, grows far above the noise of the face's offset along its
// normal. Measured against the axis's own noise about its own rest, the
// 6 mm presses, each held over several samples, still show. A knob with
// the same slips and one sample that jumps 8 mm along its axis shows no
// press: a press is held.
TEST(WeightedArticulation, AButtonsPressShowsUnderSlipsAcrossItsFace) {
  const Vector3d axis(0, -1, 0), centre(0.1, -0.2, 0.5), across1(1, 0, 0), across2(0, 0, 1);
  auto pressed_at = [](int i) { return i % 10 >= 5 && i % 10 <= 8; };
  auto track = [&](bool button, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, 1);
    Track t;
    double spin = 0;
    Vector3d slip = Vector3d::Zero();
    for (int i = 0; i < 30; ++i) {
      double along = button && pressed_at(i) ? 0.006 : 0.0;
      if (!button && i == 13) along = 0.008;  // one sample jumps
      spin += 0.15 * noise(rng);
      slip += 0.006 * (noise(rng) * across1 + noise(rng) * across2);
      const Eigen::AngleAxisd turn(spin, axis);
      t.positions.push_back(centre + along * axis + slip + 0.0005 * Vector3d(noise(rng), noise(rng), noise(rng)));
      t.rotations.emplace_back(turn * Eigen::AngleAxisd(0.005 * noise(rng), Vector3d(noise(rng), noise(rng), noise(rng)).normalized()));
      t.information.push_back(information(0.005, 0.001, {}, {}));
    }
    return t;
  };
  const Articulation button = estimate_articulation(track(true, 31));
  ASSERT_EQ(button.type, "revolute") << articulation_json(button);
  EXPECT_LT(axis_error(button.slide_axis, axis), 0.15);
  EXPECT_LT(button.slide_bic, button.revolute.bic);
  ASSERT_EQ(button.slide.size(), 30u);
  int pressed_found = 0, rest_found = 0;
  for (int i = 0; i < 30; ++i) {
    if (pressed_at(i)) pressed_found += std::abs(std::abs(button.slide[i]) - 0.006) < 0.002;
    else rest_found += button.slide[i] != 0;
  }
  EXPECT_GE(pressed_found, 10);  // of 12
  EXPECT_LE(rest_found, 1);
  const Articulation knob = estimate_articulation(track(false, 32));
  ASSERT_EQ(knob.type, "revolute") << articulation_json(knob);
  EXPECT_GE(knob.slide_bic, knob.revolute.bic);
}

TEST(WeightedArticulation, APlateThatSlidesInItsOwnPlaneIsFixed) {
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0, 1);
  const Vector3d centre(0.0, 0.1, 0.8);
  Track t;
  double slide = 0, turn = 0;
  for (int i = 0; i < 30; ++i) {
    slide += 0.004 * noise(rng);
    turn += 0.03 * noise(rng);
    t.positions.push_back(centre + slide * Vector3d(0.8, 0.6, 0) + 0.0005 * Vector3d(noise(rng), noise(rng), noise(rng)));
    t.rotations.emplace_back(Eigen::AngleAxisd(turn, Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.01 * noise(rng), Vector3d(noise(rng), noise(rng), noise(rng)).normalized()));
    t.information.push_back(information(0.01, 0.0005, {Vector3d::UnitZ()}, {Vector3d::UnitX(), Vector3d::UnitY()}));
  }
  const Articulation weighted = estimate_articulation(t);
  EXPECT_EQ(weighted.type, "fixed") << articulation_json(weighted);
  EXPECT_NE(estimate_articulation(without_information(t)).type, "fixed");
}

// Real motions, seen in every direction, noise at the floors: a lid's hinge
// and a drawer's slide come out as they are.
TEST(WeightedArticulation, RealHingesAndSlidesAreFound) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 1);
  const Vector3d hinge_axis = Vector3d(1, 0.2, 0).normalized(), hinge_point(0, 0.3, 0.9);
  const Vector3d arm(0, -0.15, 0.02);
  Track lid, drawer;
  const Vector3d slide_dir = Vector3d(0, -1, 0.05).normalized();
  for (int i = 0; i < 25; ++i) {
    const Eigen::AngleAxisd turn(1.3 * i / 24.0, hinge_axis);
    const Eigen::AngleAxisd wobble(0.015 * noise(rng), Vector3d(noise(rng), noise(rng), noise(rng)).normalized());
    lid.positions.push_back(hinge_point + turn * arm + 0.001 * Vector3d(noise(rng), noise(rng), noise(rng)));
    lid.rotations.emplace_back(wobble * turn);
    lid.information.push_back(information(0.0175, 0.001, {}, {}));
    drawer.positions.push_back(Vector3d(0.2, 0, 0.4) + 0.3 * i / 24.0 * slide_dir +
                               0.001 * Vector3d(noise(rng), noise(rng), noise(rng)));
    drawer.rotations.emplace_back(wobble);
    drawer.information.push_back(information(0.0175, 0.001, {}, {}));
  }
  const Articulation a = estimate_articulation(lid);
  ASSERT_EQ(a.type, "revolute") << articulation_json(a);
  EXPECT_LT(axis_error(a.axis, hinge_axis), 0.03);
  const Vector3d off = (a.origin - hinge_point) - (a.origin - hinge_point).dot(hinge_axis) * hinge_axis;
  EXPECT_LT(off.norm(), 0.01) << articulation_json(a);
  EXPECT_NEAR(a.range_hi - a.range_lo, 1.3, 0.05);
  const Articulation b = estimate_articulation(drawer);
  ASSERT_EQ(b.type, "prismatic") << articulation_json(b);
  EXPECT_LT(axis_error(b.axis, slide_dir), 0.02);
  EXPECT_NEAR(b.range_hi - b.range_lo, 0.3, 0.01);
}

// A still part with noise at the floors stays fixed.
TEST(WeightedArticulation, AStillPartIsFixed) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0, 1);
  Track t;
  for (int i = 0; i < 30; ++i) {
    t.positions.push_back(Vector3d(0.1, 0.2, 0.3) + 0.001 * Vector3d(noise(rng), noise(rng), noise(rng)));
    t.rotations.emplace_back(Eigen::AngleAxisd(0.0175 * noise(rng), Vector3d(noise(rng), noise(rng), noise(rng)).normalized()));
    t.information.push_back(information(0.0175, 0.001, {}, {}));
  }
  const Articulation a = estimate_articulation(t);
  EXPECT_EQ(a.type, "fixed") << articulation_json(a);
  EXPECT_GT(a.p_fixed, 0.9);
}

}  // namespace
}  // namespace efc::pipeline
