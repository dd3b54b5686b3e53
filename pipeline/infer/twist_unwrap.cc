#include "pipeline/infer/twist_unwrap.h"

#include <cmath>
#include <limits>

namespace efc::pipeline {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

// A hand's angular speed changes by about this much a frame, turning a knob
// (rad/frame^2): from rest to a fast turn of 0.6 rad a frame within two
// frames. A branch half a turn off changes it by pi.
constexpr double kAccelerationScale = 0.35;
// Dropping a frame costs what a change of speed of twice that costs.
constexpr double kDropCost = 4.0;
// A new grasp starts within this of where the last one ended (rad): it
// takes the nearest branch.
constexpr double kRegraspScale = 0.5;
// How many samples back a kept one may follow the last kept one: up to six
// dropped in a row (a fifth of a second; a hand seen edge on as it grasps
// reads a quarter turn off for four frames: s0012's knob).
constexpr int kWindow = 7;
// The branches a step between two kept samples may take: its difference
// reduced to (-pi/2, pi/2], plus -1, 0 or +1 half turns.
constexpr int kBranches = 3;

double to_half_turn(double a) {
  double r = std::remainder(a, kPi);  // [-pi/2, pi/2]
  if (r <= -kPi / 2) r += kPi;
  return r;
}

}  // namespace

std::vector<double> unwrap_half_turns(const std::vector<double>& twist, const std::vector<bool>& held,
                                      int regrasp_frames) {
  std::vector<double> out(twist.size(), std::numeric_limits<double>::quiet_NaN());
  std::vector<int> frame;
  std::vector<double> t;
  for (size_t f = 0; f < twist.size(); ++f)
    if (std::isfinite(twist[f])) frame.push_back(static_cast<int>(f)), t.push_back(twist[f]);
  const int m = static_cast<int>(t.size());
  if (m == 0) return out;
  // grasp[f]: which grasp frame f belongs to (a new one after the hand
  // let go for more than regrasp_frames frames).
  std::vector<int> grasp(twist.size(), 0);
  for (size_t f = 0, away = 0; f < twist.size(); ++f) {
    const bool holds = f < held.size() && held[f];
    grasp[f] = f == 0 ? 0 : grasp[f - 1] + (holds && away > static_cast<size_t>(regrasp_frames) ? 1 : 0);
    away = holds ? 0 : away + 1;
  }

  // State (i, back, b): sample i kept, the last kept before it i - back
  // (back == 0: i is the first kept), the step between them on branch b.
  // cost: the least cost of a course ending so; from: its predecessor.
  const int per_sample = (kWindow + 1) * kBranches;
  auto index = [&](int i, int back, int b) { return (i * (kWindow + 1) + back) * kBranches + b; };
  std::vector<double> cost(static_cast<size_t>(m) * per_sample, kInf);
  std::vector<int> from(cost.size(), -1);
  // The step from sample p to sample i on branch b, and the speed it
  // leaves the hand with (0 after a regrasp).
  auto step = [&](int p, int i, int b) { return to_half_turn(t[i] - t[p]) + (b - 1) * kPi; };
  auto regrasp = [&](int p, int i) { return grasp[frame[i]] != grasp[frame[p]]; };
  auto speed = [&](int p, int i, int b) {
    return regrasp(p, i) ? 0.0 : step(p, i, b) / (frame[i] - frame[p]);
  };
  auto sq = [](double x) { return x * x; };

  for (int i = 0; i < m; ++i) {
    // The first kept sample: those before it dropped.
    if (i < kWindow) cost[index(i, 0, 1)] = kDropCost * i;
    for (int back = 1; back <= kWindow && back <= i; ++back) {
      const int p = i - back;
      const bool new_grasp = regrasp(p, i);
      for (int b = 0; b < kBranches; ++b) {
        if (new_grasp && b != 1) continue;  // a new grasp: the nearest branch
        const double d = step(p, i, b);
        const double v = speed(p, i, b);
        double best = kInf;
        int arg = -1;
        for (int pb = 0; pb <= kWindow && pb <= p; ++pb)
          for (int bb = 0; bb < kBranches; ++bb) {
            const double c = cost[index(p, pb, bb)];
            if (c == kInf) continue;
            const double v_in = pb == 0 ? 0.0 : speed(p - pb, p, bb);
            const double move = new_grasp ? sq(d / kRegraspScale) : sq((v - v_in) / kAccelerationScale);
            const double total = c + move + kDropCost * (back - 1);
            if (total < best) best = total, arg = index(p, pb, bb);
          }
        cost[index(i, back, b)] = best;
        from[index(i, back, b)] = arg;
      }
    }
  }
  // The last kept sample: those after it dropped.
  double best = kInf;
  int end = -1;
  for (int i = std::max(0, m - kWindow); i < m; ++i)
    for (int k = 0; k < per_sample; ++k) {
      const double c = cost[static_cast<size_t>(i) * per_sample + k] + kDropCost * (m - 1 - i);
      if (c < best) best = c, end = i * per_sample + k;
    }
  // Back along the course: the steps, then the twists from the first.
  std::vector<int> course;
  for (int s = end; s >= 0; s = from[s]) course.push_back(s);
  double u = 0;
  for (auto it = course.rbegin(); it != course.rend(); ++it) {
    const int i = *it / per_sample, back = (*it % per_sample) / kBranches, b = *it % kBranches;
    u = back == 0 ? t[i] : u + step(i - back, i, b);
    out[frame[i]] = u;
  }
  return out;
}

}  // namespace efc::pipeline
