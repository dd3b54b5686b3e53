// The articulation estimator (pipeline/articulation): exact and noisy
// synthetic tracks of every joint type, pose tracks, model selection at the
// edges (a part that never moves, a short arc, a long straight slide), bad
// track files, and the real TUM tracks in ../shared/data/tum-articulation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "pipeline/articulation/articulation.h"

namespace efc::pipeline {
namespace {

using Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;

// A point at `radius` from a hinge through `origin` about `axis`, swung
// from 0 to `sweep` over n samples, with Gaussian noise of `sigma` (m).
Track hinge_track(const Vector3d& axis, const Vector3d& origin, double radius, double sweep, int n, double sigma,
                  bool poses, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, sigma);
  Vector3d arm = axis.unitOrthogonal() * radius;
  Track t;
  for (int i = 0; i < n; ++i) {
    const double th = sweep * i / (n - 1);
    const Eigen::AngleAxisd turn(th, axis.normalized());
    t.positions.push_back(origin + turn * arm + Vector3d(noise(rng), noise(rng), noise(rng)));
    if (poses) {
      const Eigen::AngleAxisd wobble(noise(rng) * 0.5, Vector3d(noise(rng), noise(rng), 1).normalized());
      t.rotations.push_back(Eigen::Quaterniond(turn * wobble * Eigen::AngleAxisd(0.3, Vector3d::UnitX())));
    }
  }
  return t;
}

Track slide_track(const Vector3d& dir, const Vector3d& start, double length, int n, double sigma, bool poses,
                  unsigned seed = 2) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, sigma);
  Track t;
  for (int i = 0; i < n; ++i) {
    t.positions.push_back(start + dir.normalized() * (length * i / (n - 1)) +
                          Vector3d(noise(rng), noise(rng), noise(rng)));
    if (poses) t.rotations.push_back(Eigen::Quaterniond(Eigen::AngleAxisd(0.2 + noise(rng), Vector3d::UnitY())));
  }
  return t;
}

double axis_error(const Vector3d& a, const Vector3d& b) {
  return std::acos(std::min(1.0, std::fabs(a.normalized().dot(b.normalized()))));
}

// Distance from p to the line through o along a.
double line_distance(const Vector3d& p, const Vector3d& o, const Vector3d& a) {
  const Vector3d d = p - o;
  return (d - d.dot(a.normalized()) * a.normalized()).norm();
}

TEST(Articulation, ExactArcIsRevoluteWithItsAxisOriginRadiusAndRange) {
  const Vector3d axis = Vector3d(0.2, -0.1, 1).normalized(), origin(0.3, -0.2, 0.9);
  const Articulation a = estimate_articulation(hinge_track(axis, origin, 0.45, 1.2, 40, 0, false));
  EXPECT_EQ(a.type, "revolute");
  EXPECT_LT(axis_error(a.axis, axis), 1e-6);
  EXPECT_GT(a.axis.dot(axis), 0);  // the motion is positive about the reported axis
  EXPECT_LT(line_distance(a.origin, origin, axis), 1e-6);
  EXPECT_NEAR(a.radius, 0.45, 1e-6);
  EXPECT_NEAR(a.range_lo, 0, 1e-9);
  EXPECT_NEAR(a.range_hi, 1.2, 1e-6);
}

TEST(Articulation, NoisyHandTracksOfHingesAreRevolute) {
  // A hand on a cabinet door handle: 5 mm of tracking noise, 60-90 degrees.
  // Over such an arc the rim's curvature, and with it the hinge line, is
  // known to a few centimetres at most (the fit is the geometric maximum
  // likelihood); the axis direction much better.
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Vector3d axis = Vector3d(0.05 * seed, 0.1, 1).normalized(), origin(0.1, 0.4, 1.0);
    const double radius = 0.25 + 0.03 * seed, sweep = 1.0 + 0.03 * seed;
    const Articulation a = estimate_articulation(hinge_track(axis, origin, radius, sweep, 50, 0.005, false, seed));
    EXPECT_EQ(a.type, "revolute") << seed;
    EXPECT_LT(axis_error(a.axis, axis), 0.05) << seed;
    EXPECT_LT(line_distance(a.origin, origin, axis), 0.04) << seed;
    EXPECT_NEAR(a.radius, radius, 0.04) << seed;
  }
}

TEST(Articulation, StraightSlidesArePrismaticEvenWithNoise) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Vector3d dir(1, 0.3 * seed, -0.2);
    const Articulation a = estimate_articulation(slide_track(dir, Vector3d(0, 0, 1), 0.35, 30, 0.004, false, seed));
    EXPECT_EQ(a.type, "prismatic") << seed;
    EXPECT_LT(axis_error(a.axis, dir), 0.05) << seed;
    EXPECT_GT(a.axis.dot(dir), 0) << seed;
    EXPECT_NEAR(a.range_hi - a.range_lo, 0.35, 0.02) << seed;
  }
  // Exact: the simplest model that explains it, not a huge circle.
  EXPECT_EQ(estimate_articulation(slide_track(Vector3d(0, 1, 0), Vector3d::Zero(), 0.4, 20, 0, false)).type,
            "prismatic");
}

TEST(Articulation, APartThatNeverMovesIsFixed) {
  // Only the tracker's noise: no model with more parameters pays for itself.
  for (unsigned seed = 1; seed <= 20; ++seed) {
    EXPECT_EQ(estimate_articulation(slide_track(Vector3d::UnitX(), Vector3d(0.2, 0.1, 0.8), 0, 40, 0.003, false, seed)).type,
              "fixed")
        << seed;
    EXPECT_EQ(estimate_articulation(slide_track(Vector3d::UnitX(), Vector3d(0.2, 0.1, 0.8), 0, 40, 0.003, true, seed)).type,
              "fixed")
        << seed;
  }
  EXPECT_EQ(estimate_articulation(slide_track(Vector3d::UnitX(), Vector3d::Zero(), 0, 10, 0, false)).type, "fixed");
}

TEST(Articulation, PoseTracksUseTheRotation) {
  // A marker on a door 0.6 m from the hinge, 2 mm and ~0.1 degree noise.
  const Vector3d axis = Vector3d(0, 0.1, 1).normalized(), origin(-0.4, 0.2, 2.0);
  const Articulation a = estimate_articulation(hinge_track(axis, origin, 0.6, 1.3, 60, 0.002, true));
  EXPECT_EQ(a.type, "revolute");
  EXPECT_LT(axis_error(a.axis, axis), 0.02);
  EXPECT_LT(line_distance(a.origin, origin, axis), 0.01);
  EXPECT_NEAR(a.radius, 0.6, 0.01);
  EXPECT_NEAR(a.range_hi, 1.3, 0.03);
  // A drawer carrying its marker without turning.
  const Articulation d = estimate_articulation(slide_track(Vector3d(0, -1, 0.1), Vector3d(0, 0, 1), 0.3, 25, 0.002, true));
  EXPECT_EQ(d.type, "prismatic");
  EXPECT_NEAR(d.p_prismatic, 1.0, 1e-6);
}

TEST(Articulation, JsonHasTheContractsKeys) {
  const Articulation a = estimate_articulation(hinge_track(Vector3d::UnitZ(), Vector3d::Zero(), 0.3, 1.0, 20, 0, false));
  const std::string j = articulation_json(a);
  for (const char* key : {"\"type\":\"revolute\"", "\"axis\":", "\"origin\":", "\"range\":", "\"residual\":",
                          "\"scores\":", "\"radius\":"})
    EXPECT_NE(j.find(key), std::string::npos) << key << " in " << j;
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}

TEST(ArticulationTrackFile, BadLinesAreLocatedAndShortTracksRefused) {
  Diagnostics diags;
  Track t;
  const std::string bad = write_temp("efc-track-bad.txt", "# x y z\n0 0 0\n0.1 abc 0\n0.2 0 nan\n1 2\n");
  EXPECT_FALSE(read_track(bad, TrackFormat::Xyz, diags, &t));
  ASSERT_EQ(diags.error_count(), 3u);
  EXPECT_EQ(diags.items()[0].code, "E1030");
  EXPECT_EQ(diags.items()[0].line, 3);
  EXPECT_EQ(diags.items()[0].col, 5);
  EXPECT_EQ(diags.items()[1].line, 4);
  EXPECT_EQ(diags.items()[2].line, 5);
  Diagnostics short_diags;
  Track s;
  EXPECT_FALSE(read_track(write_temp("efc-track-short.txt", "0 0 0\n1 1 1\n"), TrackFormat::Xyz, short_diags, &s));
  EXPECT_EQ(short_diags.items().at(0).code, "E1031");
  Diagnostics missing;
  bool io = false;
  EXPECT_FALSE(read_track("/nonexistent/track.txt", TrackFormat::Tum, missing, &s, &io));
  EXPECT_TRUE(io);
  // hands.txt (t x y z, nan when no hand) reads as xyz, skipping the nan rows.
  Diagnostics ok;
  Track h;
  EXPECT_TRUE(read_track(write_temp("efc-track-hands.txt", "# t x y z\n0 nan nan nan\n0.1 1 2 3\n0.2 1 2 4\n0.3 1 2 5\n"),
                         TrackFormat::Xyz, ok, &h));
  EXPECT_EQ(h.size(), 3u);
  EXPECT_EQ(h.positions[0], Vector3d(1, 2, 3));
}

// The real tracks (TUM, shared/data): every one typed right, hinges with a
// radius a piece of furniture could have.
TEST(ArticulationTum, RealTracksAreTypedRight) {
  const std::filesystem::path data = std::filesystem::path(EFC_SOURCE_DIR) / ".." / "shared" / "data" / "tum-articulation";
  if (!std::filesystem::exists(data)) GTEST_SKIP() << "no " << data << " (shared data not present)";
  Diagnostics diags;
  Track door, drawer;
  ASSERT_TRUE(read_track((data / "door.txt").string(), TrackFormat::Pose7, diags, &door));
  ASSERT_TRUE(read_track((data / "drawer.txt").string(), TrackFormat::Pose7, diags, &drawer));
  const Articulation d = estimate_articulation(door);
  EXPECT_EQ(d.type, "revolute");
  EXPECT_GT(d.range_hi - d.range_lo, 0.8);  // the door swings about 70 degrees
  EXPECT_EQ(estimate_articulation(drawer).type, "prismatic");
  int cabinets = 0;
  for (const auto& e : std::filesystem::directory_iterator(data / "cabinet_one")) {
    Track t;
    ASSERT_TRUE(read_track(e.path().string(), TrackFormat::Xyz, diags, &t)) << e.path();
    const Articulation a = estimate_articulation(t);
    EXPECT_EQ(a.type, "revolute") << e.path();
    EXPECT_GT(a.radius, 0.2) << e.path();
    EXPECT_LT(a.radius, 0.8) << e.path();
    ++cabinets;
  }
  EXPECT_EQ(cabinets, 10);
}

}  // namespace
}  // namespace efc::pipeline
