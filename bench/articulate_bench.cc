// Articulation benchmark (bench/README.md): the time `efc articulate` (and
// later `efc infer`'s articulation stage) spends telling the joint of one
// track, set against the budget of 1 s per part.
//
//   hinge_points/N   a noisy hand track on a door handle (N samples, xyz):
//                    PCA plane, circle, Gauss-Newton on the 3D circle, and the
//                    line and the fixed point to compare
//   hinge_poses/N    the same door as a 6-DoF pose track (axis from the
//                    rotations, the axis point with reweighting)
//   tum_door         the real door (413 poses, ../shared/data when present)
// 300 samples is a 300-frame recording's track; 3000 a long one.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>

#include "pipeline/articulation/articulation.h"

namespace {

using Eigen::Vector3d;

efc::pipeline::Track door_track(int n, bool poses) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 0.004);
  const Vector3d axis = Vector3d(0.05, 0.1, 1).normalized(), origin(0.3, 0.6, 1.0);
  efc::pipeline::Track t;
  for (int i = 0; i < n; ++i) {
    const Eigen::AngleAxisd turn(1.4 * i / (n - 1), axis);
    t.positions.push_back(origin + turn * (axis.unitOrthogonal() * 0.5) + Vector3d(noise(rng), noise(rng), noise(rng)));
    if (poses) t.rotations.push_back(Eigen::Quaterniond(turn));
  }
  return t;
}

void run(benchmark::State& state, const efc::pipeline::Track& track) {
  for (auto _ : state) benchmark::DoNotOptimize(efc::pipeline::estimate_articulation(track));
  state.counters["samples"] = static_cast<double>(track.size());
}

void BM_HingePoints(benchmark::State& state) { run(state, door_track(static_cast<int>(state.range(0)), false)); }
void BM_HingePoses(benchmark::State& state) { run(state, door_track(static_cast<int>(state.range(0)), true)); }

void BM_TumDoor(benchmark::State& state) {
  const std::string path = std::string(EFC_SOURCE_DIR) + "/../shared/data/tum-articulation/door.txt";
  efc::Diagnostics diags;
  efc::pipeline::Track track;
  if (!std::filesystem::exists(path) || !efc::pipeline::read_track(path, efc::pipeline::TrackFormat::Pose7, diags, &track)) {
    state.SkipWithError("no ../shared/data/tum-articulation/door.txt");
    return;
  }
  run(state, track);
}

BENCHMARK(BM_HingePoints)->Name("hinge_points")->Arg(300)->Arg(3000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HingePoses)->Name("hinge_poses")->Arg(300)->Arg(3000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TumDoor)->Name("tum_door")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
