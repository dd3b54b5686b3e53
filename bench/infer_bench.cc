// Inference benchmark (bench/README.md): `efc synth` renders a 300-frame
// 640x480 sequence with realistic noise of each spec into a temporary folder,
// then `efc infer`'s stages run on it as the command runs them
// (efc::pipeline::infer_sequence, then write_infer_output), timed per stage.
//
//   infer_bench [--frames N] [--width W] [--height H] [--noise L] [--threads T]
//               [--seed S] [--json FILE]
//
// Prints, per spec, the seconds of each stage of report.json's "stages"
// (observations, ego_motion, part_motion, grip_motion, articulation,
// reconstruction, templates), the whole infer (infer_sequence + writing the output, wall and
// CPU), and the goals: articulation <= 1 s, the whole infer <= 30 s on
// 2 cores (--threads 2, the CLI's default). Specs: EFC_BENCH_SPECS (default
// stove, microwave, kitchen_drawer: small knobs, a door and small buttons, a
// drawer); EFC_BENCH_FRAMES sets --frames. Rendering is not timed (synth_bench
// does that). Exit 1 when a spec cannot be rendered or inferred.
#include <stdlib.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compiler/core/load.h"
#include "pipeline/infer/infer.h"
#include "synth/synth.h"
#include "bench/spec_list.h"

namespace fs = std::filesystem;

namespace {

const char* const kStages[] = {"observations", "ego_motion",     "part_motion", "grip_motion",
                               "articulation", "reconstruction", "axis_prior",  "templates"};
constexpr double kArticulationGoal = 1.0;  // s
constexpr double kInferGoal = 30.0;        // s, on 2 cores


double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A temporary folder removed on every exit path.
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    const char* tmp = std::getenv("TMPDIR");
    std::string templ = std::string(tmp && *tmp ? tmp : "/tmp") + "/efc-infer-bench-XXXXXX";
    if (mkdtemp(templ.data())) path = templ;
  }
  ~ScratchDir() {
    std::error_code ec;
    if (!path.empty()) fs::remove_all(path, ec);
  }
};

void print_diags(const efc::Diagnostics& diags) {
  for (const efc::Diagnostic& d : diags.items())
    if (d.severity == efc::Severity::Error) std::fprintf(stderr, "%s\n", efc::format_text(d).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 300, width = 640, height = 480, threads = 2;
  uint64_t seed = 0;
  if (const char* env = std::getenv("EFC_BENCH_FRAMES"); env && *env) frames = std::atoi(env);
  std::string noise = "realistic", json_path;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--frames") frames = std::atoi(v.c_str());
    else if (a == "--width") width = std::atoi(v.c_str());
    else if (a == "--height") height = std::atoi(v.c_str());
    else if (a == "--noise") noise = v;
    else if (a == "--threads") threads = std::atoi(v.c_str());
    else if (a == "--seed") seed = std::strtoull(v.c_str(), nullptr, 10);
    else if (a == "--json") json_path = v;
    else {
      argc = -1;
      break;
    }
  }
  if (argc < 0 || argc % 2 == 0 || frames < 2 || width < 16 || height < 16 || threads < 1) {
    std::fprintf(stderr,
                 "usage: infer_bench [--frames N] [--width W] [--height H] [--noise L] [--threads T] [--seed S] "
                 "[--json FILE]\n");
    return 2;
  }
  ScratchDir scratch;
  if (scratch.path.empty()) {
    std::fprintf(stderr, "infer_bench: cannot create a temporary folder\n");
    return 2;
  }
  const std::string examples = std::string(EFC_SOURCE_DIR) + "/examples/";
  nlohmann::json results = nlohmann::json::array();
  std::printf("Inference: efc infer on efc synth sequences, %d frames at %dx%d, noise %s, %d threads (seconds)\n",
              frames, width, height, noise.c_str(), threads);
  std::printf("%-16s %6s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s\n", "spec", "parts", "observ", "ego", "part_mo",
              "grip_mo", "artic", "recon", "axes", "templ", "infer", "total", "cpu");
  std::fflush(stdout);
  int status = 0;
  double worst_artic = 0, worst_total = 0;
  int measured = 0;
  for (const std::string& spec : efc_bench::example_stems("stove,microwave,kitchen_drawer")) {
    efc::Diagnostics diags;
    const std::string path = examples + spec + ".json";
    std::optional<efc::Object> obj = efc::load_spec(path, {}, diags);
    if (!obj) {
      std::fprintf(stderr, "infer_bench: cannot load %s\n", path.c_str());
      print_diags(diags);
      status = 1;
      continue;
    }
    efc::synth::SynthOptions opts;
    opts.frames = frames;
    opts.width = width;
    opts.height = height;
    opts.seed = seed;
    opts.spec_json = efc_bench::read_text(path);
    std::string error;
    int line = 0;
    bool io = false;
    efc::parse_profile("sweep", &opts.profile, &error, &line, &io);
    if (!efc::synth::parse_noise_level(noise, &opts.knobs.noise)) {
      std::fprintf(stderr, "infer_bench: unknown noise level '%s'\n", noise.c_str());
      return 2;
    }
    const fs::path seq_dir = scratch.path / spec, out_dir = scratch.path / (spec + "-infer");
    efc::synth::SynthStats synth_stats;
    if (efc::synth::synthesize(*obj, opts, seq_dir.string(), diags, &synth_stats) != 0) {
      std::fprintf(stderr, "infer_bench: efc synth failed on %s\n", spec.c_str());
      print_diags(diags);
      status = 1;
      continue;
    }

    efc::pipeline::InferOptions iopts;
    iopts.observe.threads = threads;
    iopts.templates.threads = threads;
    efc::pipeline::InferResult result;
    efc::Diagnostics idiags;
    const double cpu0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    int rc = efc::pipeline::infer_sequence(seq_dir.string(), iopts, idiags, &result);
    const double infer_s = since(t0);
    if (rc == 0) rc = efc::pipeline::write_infer_output(result, out_dir.string(), idiags);
    const double total_s = since(t0), cpu_s = cpu_seconds() - cpu0;
    std::error_code ec;
    fs::remove_all(seq_dir, ec);
    fs::remove_all(out_dir, ec);
    if (rc != 0) {
      std::printf("%-16s infer failed (exit %d) after %.2f s\n", spec.c_str(), rc, total_s);
      std::fflush(stdout);
      print_diags(idiags);
      status = 1;
      continue;
    }
    std::map<std::string, double> stage_s;
    for (const auto& s : result.report["stages"]) stage_s[s["name"].get<std::string>()] = s["seconds"].get<double>();
    const size_t parts = result.report.contains("parts") ? result.report["parts"].size() : 0;
    std::printf("%-16s %6zu", spec.c_str(), parts);
    nlohmann::json row = {{"spec", spec},       {"frames", frames},   {"width", width},     {"height", height},
                          {"noise", noise},     {"threads", threads}, {"parts", parts},     {"infer_seconds", infer_s},
                          {"total_seconds", total_s}, {"cpu_seconds", cpu_s},
                          {"synth_seconds", synth_stats.seconds}};
    for (const char* name : kStages) {
      const auto it = stage_s.find(name);
      if (it == stage_s.end()) std::printf(" %8s", "-");
      else std::printf(" %8.3f", it->second);
      row["stages"][name] = it == stage_s.end() ? nlohmann::json() : nlohmann::json(it->second);
    }
    std::printf(" %8.2f %8.2f %8.2f\n", infer_s, total_s, cpu_s);
    std::fflush(stdout);
    worst_artic = std::max(worst_artic, stage_s.count("articulation") ? stage_s["articulation"] : 0.0);
    worst_total = std::max(worst_total, total_s);
    ++measured;
    results.push_back(row);
  }
  std::printf("\ncolumns: observ = observations, ego = ego_motion, part_mo = part_motion, grip_mo = grip_motion\n"
              "(the hand's points tracked while it holds a receptor), artic = articulation,\n"
              "recon = reconstruction, axes = axis_prior (the body's axes), templ = templates (report.json's\n"
              "stages); infer = infer_sequence wall,\n"
              "total = + writing spec.json, meshes/, report.json (what `efc infer` does); cpu = CPU seconds of both\n");
  if (measured > 0) {
    std::printf("goal: articulation <= %.0f s: %s (worst %.3f s)\n", kArticulationGoal,
                worst_artic <= kArticulationGoal ? "met" : "MISSED", worst_artic);
    std::printf("goal: whole infer <= %.0f s on 2 cores: %s (worst %.2f s, %d threads%s)\n", kInferGoal,
                worst_total <= kInferGoal ? "met" : "MISSED", worst_total, threads,
                frames == 300 && width == 640 && height == 480 ? "" : "; not the goal's 300 frames at 640x480");
  }
  if (!json_path.empty()) std::ofstream(json_path) << results.dump(2) << "\n";
  return status;
}
