// Playback benchmark (bench/README.md): the cost of the function templates
// against MuJoCo's own step, on the same compiled model in the same run.
//
// Each spec is compiled as `efc play` compiles it (write_mujoco_model with
// drive_receptors, mj_loadXML), once per process. One benchmark iteration runs
// episodes of the same length from the same reset state (keyframe `initial`)
// back to back, raw, templates, templates, raw (ABBA), so both kinds see the
// same machine load and neither always runs first (a fifth episode, the
// templates one again with a clock around the template part, gives
// template_ns and template_pct):
//   raw        mj_step only, on the same trajectory: before timing, one
//              templates episode records d->ctrl (and the air forces on free
//              bodies) each step; the raw episode copies that row in and calls
//              mj_step, so MuJoCo does the same work in both (the copy costs a
//              few ns). Fluid droplets are moved by the binding itself, so for
//              play_fluid/ the two trajectories differ.
//   templates  the same recorded inputs (the receptor drives' ctrl, which
//              the profile press:2 set during recording), then
//              Controller::step (the templates, which recompute the effect
//              actuators' ctrl and the air forces), then mj_step: the only
//              difference from raw is template evaluation. (Evaluating the
//              profile itself is the harness standing in for an agent, not
//              template cost: it is kept out of both episodes.)
// Counters (medians over the iterations of a repetition; the report gives the
// median of 5 repetitions):
//   raw_steps_per_s, tmpl_steps_per_s   steps per second of each episode
//   overhead_pct     t_templates / t_raw - 1 of the same iteration (each the
//                    mean of its two episodes), end to end
//   template_pct     time inside Controller::step, timed in the loop
//                    less the cost of a clock read (clock_ns, calibrated),
//                    over the raw episode's time: the cost of template
//                    evaluation as a % of a step
//   template_ns      that time per step in ns
//   warnings         MuJoCo warnings (e.g. an unstable simulation reset):
//                    figures of a spec with warnings are not meaningful
//   episode_steps    steps per episode (see kEpisodeBudget)
// Specs with a fluid effect (particles) are reported as play_fluid/<spec>,
// all others as play/<spec>.
#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "backends/common/lowering.h"
#include "backends/mujoco/mujoco_backend.h"
#include "bench/bench_common.h"
#include "harness/mujoco_errors.h"
#include "harness/play.h"
#include "runtime/efc_profile.h"
#include "runtime/mujoco/efc_mujoco.h"

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kRepetitions = 5;
constexpr double kMinTime = 0.1;    // s per repetition
// Episode length: as many steps as take about kEpisodeBudget s of raw mj_step
// (estimated once per spec), between kMinSteps and kMaxSteps. Small objects
// get 500 steps (1 s at 2 ms); the 200-part spec and the particle examples,
// whose steps cost milliseconds, get fewer, so bench/run stays short.
constexpr double kEpisodeBudget = 0.2;
constexpr int kMinSteps = 10, kMaxSteps = 500;

struct Drive {
  std::string part;
  int actuator = -1;
  double lo = 0, hi = 0, q0 = 0;
};

// The model as `efc play` builds it, plus everything its loop needs.
struct Sim {
  efc::Object obj;
  efc_bench::TempDir dir{"efc-bench-play"};
  mjModel* m = nullptr;
  mjData* d = nullptr;
  std::vector<efc_mj::FunctionBinding> table;
  std::unique_ptr<efc_mj::Controller> controller;
  std::vector<Drive> drives;
  int key = -1;
  efc::Profile profile;
  double duration = 0;
  int steps = kMaxSteps;  // per episode
  std::vector<int> free_bodies;      // bodies on a free joint (air forces)
  std::vector<mjtNum> ctrl_log;      // nu per step of a templates episode
  std::vector<mjtNum> xfrc_log;      // 6 per free body per step

  ~Sim() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }

  bool build(const std::string& path, std::string* error) {
    auto o = efc_bench::load(path, error);
    if (!o) return false;
    obj = std::move(*o);
    efc::MjcfOptions mjcf;
    mjcf.drive_receptors = true;
    std::string xml;
    efc::Diagnostics diags;
    if (!efc::write_mujoco_model(obj, dir.path().string(), mjcf, diags, &xml)) {
      *error = "write_mujoco_model failed for " + path;
      return false;
    }
    char load_error[1024] = "";
    m = mj_loadXML(xml.c_str(), nullptr, load_error, sizeof load_error);
    if (!m) {
      *error = std::string("mj_loadXML: ") + load_error;
      return false;
    }
    d = mj_makeData(m);
    key = mj_name2id(m, mjOBJ_KEY, "initial");
    table = efc::build_bindings(obj);
    controller = std::make_unique<efc_mj::Controller>(m, table.data(), static_cast<int>(table.size()));
    if (!controller->ok()) {
      *error = "Controller: " + controller->error();
      return false;
    }
    reset(true);
    for (int pi : efc::lowering::profile_driven_receptors(obj)) {
      const efc::Part& p = obj.parts[pi];
      Drive dr;
      dr.part = p.name;
      dr.actuator = mj_name2id(m, mjOBJ_ACTUATOR, ("efc_drive_" + p.name).c_str());
      const int jid = mj_name2id(m, mjOBJ_JOINT, p.name.c_str());
      if (dr.actuator < 0 || jid < 0) {
        *error = "no drive for receptor '" + p.name + "'";
        return false;
      }
      if (p.joint->has_range) {
        dr.lo = p.joint->lo;
        dr.hi = p.joint->hi;
      } else {
        dr.lo = 0;
        dr.hi = 2 * mjPI;
      }
      dr.q0 = d->qpos[m->jnt_qposadr[jid]];
      drives.push_back(dr);
    }
    profile.kind = efc::Profile::Kind::Press;
    profile.presses = 2;
    for (int j = 0; j < m->njnt; ++j)
      if (m->jnt_type[j] == mjJNT_FREE) free_bodies.push_back(m->jnt_bodyid[j]);
    // Estimate the cost of a step (after one warm-up step) to size episodes.
    reset(false);
    mj_step(m, d);
    const int probe = 5;
    const auto t0 = Clock::now();
    for (int k = 0; k < probe; ++k) mj_step(m, d);
    const double per_step = std::chrono::duration<double>(Clock::now() - t0).count() / probe;
    steps = static_cast<int>(kEpisodeBudget / std::max(per_step, 1e-9));
    steps = std::clamp(steps, kMinSteps, kMaxSteps);
    duration = steps * m->opt.timestep;
    record();
    return true;
  }

  void set_drives(double t) {
    for (const Drive& dr : drives)
      d->ctrl[dr.actuator] = efc::profile_target(profile, dr.part, dr.lo, dr.hi, dr.q0, t, duration);
  }

  // One templates episode, logging what the raw episode replays.
  void record() {
    reset(true);
    ctrl_log.assign(static_cast<size_t>(steps) * m->nu, 0);
    xfrc_log.assign(static_cast<size_t>(steps) * 6 * free_bodies.size(), 0);
    for (int k = 0; k < steps; ++k) {
      set_drives(k * m->opt.timestep);
      controller->step(m, d);
      if (m->nu) mju_copy(&ctrl_log[static_cast<size_t>(k) * m->nu], d->ctrl, m->nu);
      for (size_t b = 0; b < free_bodies.size(); ++b)
        mju_copy(&xfrc_log[(static_cast<size_t>(k) * free_bodies.size() + b) * 6],
                 d->xfrc_applied + 6 * free_bodies[b], 6);
      mj_step(m, d);
    }
  }

  void reset(bool with_controller) {
    if (key >= 0) mj_resetDataKeyframe(m, d, key);
    else mj_resetData(m, d);
    mj_forward(m, d);
    if (with_controller) controller->reset(m, d);
  }
};

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Built once per spec and shared by its repetitions.
Sim* get_sim(const efc_bench::BenchSpec& spec, std::string* error) {
  static std::map<std::string, std::unique_ptr<Sim>> sims;
  auto it = sims.find(spec.path);
  if (it == sims.end()) {
    auto sim = std::make_unique<Sim>();
    if (!sim->build(spec.path, error)) sim.reset();
    it = sims.emplace(spec.path, std::move(sim)).first;
  }
  if (!it->second && error->empty()) *error = "could not build " + spec.path;
  return it->second.get();
}

void BM_play(benchmark::State& state, const efc_bench::BenchSpec& spec) {
  efc::take_mujoco_warnings();
  std::string error;
  Sim* sim_ptr = nullptr;
  try {
    sim_ptr = get_sim(spec, &error);
  } catch (const efc::MujocoError& e) {
    error = std::string("MuJoCo error: ") + e.what();
  }
  if (!sim_ptr) return state.SkipWithError(error.c_str());
  Sim& sim = *sim_ptr;
  mjModel* m = sim.m;
  mjData* d = sim.d;
  efc_mj::Controller& controller = *sim.controller;
  const int steps = sim.steps;

  // Cost of a clock read, which every in-loop measurement carries once.
  double clock_ns = 0;
  {
    Clock::duration acc{};
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const auto a = Clock::now();
      acc += Clock::now() - a;
    }
    clock_ns = std::chrono::duration<double, std::nano>(acc).count() / n;
  }

  const int nu = m->nu;
  const size_t nfree = sim.free_bodies.size();
  // Step k's recorded inputs: every ctrl (the receptor drives the profile set
  // and the effect actuators) and the air forces on free bodies.
  auto replay_inputs = [&](int k) {
    if (nu) mju_copy(d->ctrl, &sim.ctrl_log[static_cast<size_t>(k) * nu], nu);
    for (size_t b = 0; b < nfree; ++b)
      mju_copy(d->xfrc_applied + 6 * sim.free_bodies[b],
               &sim.xfrc_log[(static_cast<size_t>(k) * nfree + b) * 6], 6);
  };
  // One episode on the recorded inputs: raw (mj_step only) or with the
  // templates (which recompute the effect actuators' ctrl and the air forces
  // themselves; no clock inside). Both kinds run this one loop, so the only
  // difference is Controller::step: with two loops, their code layout alone
  // differed by ~0.7% of a toaster step even with an empty function in
  // place of Controller::step.
  auto episode = [&](bool templates) {
    sim.reset(templates);
    const auto t0 = Clock::now();
    for (int k = 0; k < steps; ++k) {
      replay_inputs(k);
      if (templates) controller.step(m, d);
      mj_step(m, d);
    }
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };

  // Per iteration: raw, templates, templates, raw (ABBA, so a drift in machine
  // speed during the iteration and the order of episodes cancel out), then a
  // templates episode with the template part timed.
  std::vector<double> raw_s, tmpl_s, inner_s, overhead, share;
  try {
    for (auto _ : state) {
      const double raw_a = episode(false);
      const double tmpl_a = episode(true);
      const double tmpl_b = episode(true);
      const double raw_b = episode(false);
      const double raw = 0.5 * (raw_a + raw_b), tmpl = 0.5 * (tmpl_a + tmpl_b);

      sim.reset(true);
      Clock::duration inner_d{};
      for (int k = 0; k < steps; ++k) {
        replay_inputs(k);
        const auto a = Clock::now();
        controller.step(m, d);
        inner_d += Clock::now() - a;
        mj_step(m, d);
      }
      // Less the clock read each in-loop measurement carries.
      const double inner = std::max(
          0.0, std::chrono::duration<double>(inner_d).count() - steps * clock_ns * 1e-9);
      raw_s.push_back(raw);
      tmpl_s.push_back(tmpl);
      inner_s.push_back(inner);
      overhead.push_back(tmpl / raw - 1);
      share.push_back(inner / raw);
    }
  } catch (const efc::MujocoError& e) {
    return state.SkipWithError((std::string("MuJoCo error: ") + e.what()).c_str());
  }
  if (raw_s.empty()) return;
  state.counters["episode_steps"] = steps;
  state.counters["raw_steps_per_s"] = steps / median(raw_s);
  state.counters["tmpl_steps_per_s"] = steps / median(tmpl_s);
  state.counters["overhead_pct"] = 100.0 * median(overhead);
  state.counters["template_pct"] = 100.0 * median(share);
  state.counters["template_ns"] = 1e9 * median(inner_s) / steps;
  state.counters["clock_ns"] = clock_ns;
  state.counters["functions"] = static_cast<double>(sim.obj.functions.size());
  state.counters["nbody"] = m->nbody;
  state.counters["nv"] = m->nv;
  state.counters["warnings"] = static_cast<double>(efc::take_mujoco_warnings().size());
}

}  // namespace

int main(int argc, char** argv) {
  efc::install_mujoco_handlers();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  for (const efc_bench::BenchSpec& spec : efc_bench::bench_specs()) {
    // Whether it has particles decides the group; a spec that does not load
    // still gets a benchmark so the failure shows.
    std::string error;
    const auto obj = efc_bench::load(spec.path, &error);
    const std::string group = obj && efc_bench::has_fluid(*obj) ? "play_fluid/" : "play/";
    benchmark::RegisterBenchmark((group + spec.name).c_str(), BM_play, spec)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(kMinTime)
        ->Repetitions(kRepetitions)
        ->ReportAggregatesOnly(true);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
