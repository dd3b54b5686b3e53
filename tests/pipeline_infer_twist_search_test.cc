// A held knob's turn searched about its known hinge
// (pipeline/infer/twist_search.h): a hand-like shape turned about a radian
// a frame, which its registration followed only a fraction of the way,
// comes out at its true twist modulo a half turn; a frame the registration
// got right keeps the registration's twist; a frame with too few points
// has none.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "pipeline/infer/twist_search.h"

namespace {

using efc::pipeline::Cloud;
using efc::pipeline::search_twists;
using Eigen::Vector3d;
constexpr double kPi = 3.14159265358979323846;

// A palm (a 8 x 2.4 x 9 cm slab beside the axis) and a thumb (a 2 cm
// block off to one side), their surfaces sampled every 4 mm; the hinge is
// the z axis through (0, 0, 0), the fingers along it.
Cloud hand_shape() {
  Cloud c;
  auto block = [&](const Vector3d& lo, const Vector3d& hi) {
    for (double x = lo.x(); x <= hi.x() + 1e-9; x += 0.004)
      for (double y = lo.y(); y <= hi.y() + 1e-9; y += 0.004)
        for (double z = lo.z(); z <= hi.z() + 1e-9; z += 0.004) {
          const int on_face = (std::abs(x - lo.x()) < 1e-9 || std::abs(x - hi.x()) < 1e-9) +
                              (std::abs(y - lo.y()) < 1e-9 || std::abs(y - hi.y()) < 1e-9) +
                              (std::abs(z - lo.z()) < 1e-9 || std::abs(z - hi.z()) < 1e-9);
          if (on_face > 0) c.points.emplace_back(x, y, z);
        }
  };
  block(Vector3d(-0.02, 0.012, 0.0), Vector3d(0.06, 0.036, 0.09));
  block(Vector3d(0.03, -0.03, 0.01), Vector3d(0.05, -0.01, 0.03));
  return c;
}

Cloud turned(const Cloud& c, double twist, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, 0.0007);
  Cloud out;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(twist, Vector3d::UnitZ()).toRotationMatrix();
  for (const Vector3d& p : c.points) out.points.push_back(R * p + Vector3d(noise(rng), noise(rng), noise(rng)));
  return out;
}

double off_by_half_turns(double got, double truth) { return std::abs(std::remainder(got - truth, kPi)); }

TEST(PipelineInferTwistSearch, AFastTurnTheRegistrationMissedIsFoundAboutTheHinge) {
  const Cloud model = hand_shape();
  std::mt19937 rng(3);
  // At rest, a radian a frame up to 4 rad, held, back at a radian a frame.
  const std::vector<double> truth{0, 0, 1, 2, 3, 4, 4, 4, 3, 2, 1, 0, 0};
  std::vector<Cloud> clouds;
  std::vector<double> registered;
  for (size_t f = 0; f < truth.size(); ++f) {
    clouds.push_back(turned(model, truth[f], rng));
    // The registration settles a tenth of the way from its last pose, or,
    // at rest, where the part is.
    registered.push_back(f > 0 && truth[f] != truth[f - 1] ? registered.back() + 0.1 * (truth[f] - truth[f - 1])
                                                            : truth[f]);
  }
  clouds[6].points.resize(5);  // the hand hidden: too few points
  const std::vector<double> got = search_twists(clouds, model, Vector3d::UnitZ(), Vector3d::Zero(), registered);
  ASSERT_EQ(got.size(), truth.size());
  for (size_t f = 0; f < truth.size(); ++f) {
    if (f == 6) {
      EXPECT_TRUE(std::isnan(got[f]));
      continue;
    }
    EXPECT_LT(off_by_half_turns(got[f], truth[f]), 0.05) << "frame " << f;
  }
  // At rest the registration was right and stays.
  EXPECT_DOUBLE_EQ(got[0], registered[0]);
  EXPECT_DOUBLE_EQ(got[12], registered[12]);
}

}  // namespace
