// The grip's twist unwrapped by half turns (pipeline/infer/twist_unwrap.h):
// a knob's turn seen through a nearly flat hand's registration, right only
// modulo a half turn, comes back whole; a frame registered anywhere is
// dropped; a dial's full turn is followed; a new grasp starts where the
// last one ended.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "pipeline/infer/twist_unwrap.h"

namespace {

using efc::pipeline::unwrap_half_turns;
constexpr double kPi = 3.14159265358979323846;

// A knob at rest, turned at `speed` rad a frame to `peak`, held there,
// turned back, at rest again.
std::vector<double> turn_and_back(double peak, double speed) {
  std::vector<double> q(10, 0.0);
  for (double a = speed; a < peak; a += speed) q.push_back(a);
  for (int k = 0; k < 5; ++k) q.push_back(peak);
  for (double a = peak - speed; a > 0; a -= speed) q.push_back(a);
  for (int k = 0; k < 10; ++k) q.push_back(0.0);
  return q;
}

// As the hand's registration reports it: a little noise, half a turn added
// at random where the hand has turned past an eighth of a turn, then
// wrapped to (-pi, pi] as a rotation's angle is.
std::vector<double> seen_by_a_flat_hand(const std::vector<double>& q, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.03);
  std::bernoulli_distribution flip(0.5);
  std::vector<double> out;
  for (double v : q) {
    double t = v + noise(rng) + (std::abs(v) > kPi / 4 && flip(rng) ? kPi : 0.0);
    out.push_back(std::remainder(t, 2 * kPi));
  }
  return out;
}

double max_error(const std::vector<double>& got, const std::vector<double>& truth, int* dropped) {
  double worst = 0;
  *dropped = 0;
  for (size_t f = 0; f < truth.size(); ++f) {
    if (std::isnan(got[f])) {
      ++*dropped;
      continue;
    }
    worst = std::max(worst, std::abs(got[f] - truth[f]));
  }
  return worst;
}

TEST(PipelineInferTwist, ATwistSeenModuloAHalfTurnIsUnwrapped) {
  const std::vector<double> truth = turn_and_back(3.0, 0.5);
  const std::vector<bool> held(truth.size(), true);
  for (unsigned seed : {1u, 2u, 3u}) {
    const std::vector<double> seen = seen_by_a_flat_hand(truth, seed);
    int dropped = 0;
    // What the registration says is wrong by half a turn somewhere.
    EXPECT_GT(max_error(seen, truth, &dropped), 2.5) << "seed " << seed;
    const std::vector<double> got = unwrap_half_turns(seen, held, 3);
    EXPECT_LT(max_error(got, truth, &dropped), 0.15) << "seed " << seed;
    EXPECT_LE(dropped, 1) << "seed " << seed;
  }
}

TEST(PipelineInferTwist, AFrameRegisteredAnywhereIsDropped) {
  const std::vector<double> truth = turn_and_back(3.0, 0.5);
  const std::vector<bool> held(truth.size(), true);
  std::vector<double> seen = seen_by_a_flat_hand(truth, 4);
  const int edge_on = 12;  // mid-turn (1.5 rad): a hand seen edge on, registered 1.3 rad off
  ASSERT_NEAR(truth[edge_on], 1.5, 1e-9);
  seen[edge_on] = std::remainder(truth[edge_on] - 1.3, 2 * kPi);
  const std::vector<double> got = unwrap_half_turns(seen, held, 3);
  EXPECT_TRUE(std::isnan(got[edge_on]));
  int dropped = 0;
  EXPECT_LT(max_error(got, truth, &dropped), 0.15);
  EXPECT_LE(dropped, 2);
  // Frames never registered stay unknown; the others are still followed.
  seen[14] = seen[15] = std::nan("");
  const std::vector<double> gaps = unwrap_half_turns(seen, held, 3);
  EXPECT_TRUE(std::isnan(gaps[14]) && std::isnan(gaps[15]));
  EXPECT_LT(max_error(gaps, truth, &dropped), 0.15);
}

TEST(PipelineInferTwist, ADialsFullTurnIsFollowed) {
  const std::vector<double> truth = turn_and_back(2 * kPi, 0.7);
  const std::vector<bool> held(truth.size(), true);
  const std::vector<double> got = unwrap_half_turns(seen_by_a_flat_hand(truth, 5), held, 3);
  int dropped = 0;
  EXPECT_LT(max_error(got, truth, &dropped), 0.15);
  EXPECT_LE(dropped, 1);
  double top = 0;
  for (double v : got)
    if (!std::isnan(v)) top = std::max(top, v);
  EXPECT_NEAR(top, 2 * kPi, 0.15);
}

TEST(PipelineInferTwist, ANewGraspStartsWhereTheLastEnded) {
  // Turned to 1 rad and back, let go for ten frames, grasped again at rest:
  // the first twist of the new grasp reads half a turn off.
  std::vector<double> truth = turn_and_back(1.0, 0.25);
  std::vector<bool> held(truth.size(), true);
  const size_t away = truth.size();
  for (int k = 0; k < 10; ++k) truth.push_back(0.0), held.push_back(false);
  for (int k = 0; k < 5; ++k) truth.push_back(0.0), held.push_back(true);
  std::vector<double> seen = seen_by_a_flat_hand(truth, 6);
  for (size_t f = away; f < away + 10; ++f) seen[f] = std::nan("");
  seen[away + 10] = std::remainder(seen[away + 10] + kPi, 2 * kPi);
  const std::vector<double> got = unwrap_half_turns(seen, held, 3);
  EXPECT_NEAR(got[away + 10], 0.0, 0.15);
  int dropped = 0;
  EXPECT_LT(max_error(got, truth, &dropped), 0.15);
}

}  // namespace
