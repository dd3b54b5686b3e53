// Compile-time benchmark (bench/README.md). For every examples/*.json and the
// generated 200-part spec:
//   check/<spec>           efc::load_spec = read + resolve + check (`efc check`)
//   compile_mujoco/<spec>  load_spec + the mujoco backend's emit into an empty
//                          folder (`efc compile --target mujoco`, minus the CLI)
//   compile_mjcf/<spec>    load_spec + write_mujoco_model: only the MJCF and its
//                          meshes (what MuJoCo loads), without the callbacks,
//                          the copied runtime, CMakeLists.txt and README.md
//   write_files/<spec>     writing the files compile_mujoco writes, their text
//                          already in memory: the file system's share of it
//   mujoco_load/<spec>     mj_loadXML of the emitted XML: what MuJoCo itself
//                          takes to load the result (compile should be well under)
// Each is repeated 5 times and reported as mean / median / stddev (ms).
#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "backends/mujoco/mujoco_backend.h"
#include "backends/output_file.h"
#include "bench/bench_common.h"
#include "compiler/core/load.h"
#include "harness/mujoco_errors.h"

namespace fs = std::filesystem;

namespace {

constexpr int kRepetitions = 5;
constexpr double kMinTime = 0.05;  // s per repetition (bench/run stays under ~3 min)

void set_counters(benchmark::State& state, const efc::Object& obj) {
  state.counters["parts"] = static_cast<double>(obj.parts.size());
  state.counters["functions"] = static_cast<double>(obj.functions.size());
}

void BM_check(benchmark::State& state, const efc_bench::BenchSpec& spec) {
  std::string error;
  const auto obj = efc_bench::load(spec.path, &error);
  if (!obj) return state.SkipWithError(error.c_str());
  for (auto _ : state) {
    efc::Diagnostics diags;
    auto o = efc::load_spec(spec.path, efc::LoadOptions{}, diags);
    benchmark::DoNotOptimize(o);
  }
  set_counters(state, *obj);
}

// load_spec + one target's emit (the driver's work for `efc compile --target T`).
void BM_compile(benchmark::State& state, const efc_bench::BenchSpec& spec, const char* target) {
  std::string error;
  const auto obj = efc_bench::load(spec.path, &error);
  if (!obj) return state.SkipWithError(error.c_str());
  const efc::Backend* backend = efc::find_backend(target);
  if (!backend) return state.SkipWithError("target not registered");
  efc_bench::TempDir tmp("efc-bench-compile");
  const std::string out = (tmp.path() / target).string();
  for (auto _ : state) {
    // What the driver does: an empty folder, load, emit.
    std::error_code ec;
    fs::create_directory(out, ec);
    efc::Diagnostics diags;
    auto o = efc::load_spec(spec.path, efc::LoadOptions{}, diags);
    if (!o || !backend->emit(*o, out, diags)) {
      state.SkipWithError(("compile failed for " + spec.path).c_str());
      break;
    }
    state.PauseTiming();
    fs::remove_all(out, ec);
    state.ResumeTiming();
  }
  set_counters(state, *obj);
}

void BM_compile_mjcf(benchmark::State& state, const efc_bench::BenchSpec& spec) {
  std::string error;
  const auto obj = efc_bench::load(spec.path, &error);
  if (!obj) return state.SkipWithError(error.c_str());
  efc_bench::TempDir tmp("efc-bench-mjcf");
  const std::string out = (tmp.path() / "mujoco").string();
  for (auto _ : state) {
    std::error_code ec;
    fs::create_directory(out, ec);
    efc::Diagnostics diags;
    auto o = efc::load_spec(spec.path, efc::LoadOptions{}, diags);
    std::string xml;
    if (!o || !efc::write_mujoco_model(*o, out, efc::MjcfOptions{}, diags, &xml)) {
      state.SkipWithError(("write_mujoco_model failed for " + spec.path).c_str());
      break;
    }
    state.PauseTiming();
    fs::remove_all(out, ec);
    state.ResumeTiming();
  }
  set_counters(state, *obj);
}

// Writing the same files `efc compile --target mujoco` writes for this spec
// (their text already in memory; the same write_text_file), into an empty
// folder: what the file system charges for the output alone, which any tool
// producing these files would pay. compile_mujoco minus this is efc's own work.
void BM_write_files(benchmark::State& state, const efc_bench::BenchSpec& spec) {
  std::string error;
  const auto obj = efc_bench::load(spec.path, &error);
  if (!obj) return state.SkipWithError(error.c_str());
  efc_bench::TempDir tmp("efc-bench-files");
  const fs::path emitted = tmp.path() / "emitted";
  fs::create_directory(emitted);
  efc::Diagnostics diags;
  if (!efc::find_backend("mujoco")->emit(*obj, emitted.string(), diags))
    return state.SkipWithError(("compile failed for " + spec.path).c_str());
  // The output as (folder?, relative path, text), folders before their files.
  struct Entry {
    bool folder;
    std::string rel, text;
  };
  std::vector<Entry> entries;
  for (const auto& e : fs::recursive_directory_iterator(emitted)) {
    const std::string rel = fs::relative(e.path(), emitted).string();
    if (e.is_directory()) {
      entries.push_back({true, rel, {}});
    } else {
      std::ifstream in(e.path(), std::ios::binary);
      entries.push_back({false, rel, std::string(std::istreambuf_iterator<char>(in), {})});
    }
  }
  std::stable_partition(entries.begin(), entries.end(), [](const Entry& e) { return e.folder; });
  const std::string out = (tmp.path() / "mujoco").string();
  for (auto _ : state) {
    std::error_code ec;
    fs::create_directory(out, ec);
    for (const Entry& e : entries) {
      const std::string path = out + "/" + e.rel;
      if (e.folder ? !fs::create_directory(path, ec) : !efc::write_text_file(path, e.text, &error)) {
        state.SkipWithError(("cannot write " + path).c_str());
        break;
      }
    }
    state.PauseTiming();
    fs::remove_all(out, ec);
    state.ResumeTiming();
  }
  state.counters["files"] = static_cast<double>(entries.size());
  set_counters(state, *obj);
}

void BM_mujoco_load(benchmark::State& state, const efc_bench::BenchSpec& spec) {
  std::string error;
  const auto obj = efc_bench::load(spec.path, &error);
  if (!obj) return state.SkipWithError(error.c_str());
  efc_bench::TempDir tmp("efc-bench-load");
  const std::string out = (tmp.path() / "mujoco").string();
  fs::create_directory(out);
  efc::Diagnostics diags;
  if (!efc::find_backend("mujoco")->emit(*obj, out, diags))
    return state.SkipWithError(("compile failed for " + spec.path).c_str());
  const std::string xml = out + "/" + obj->name + ".xml";
  char load_error[1024] = "";
  try {
    for (auto _ : state) {
      mjModel* m = mj_loadXML(xml.c_str(), nullptr, load_error, sizeof load_error);
      if (!m) {
        state.SkipWithError((std::string("mj_loadXML: ") + load_error).c_str());
        break;
      }
      state.PauseTiming();
      mj_deleteModel(m);
      state.ResumeTiming();
    }
  } catch (const efc::MujocoError& e) {
    state.SkipWithError((std::string("MuJoCo error: ") + e.what()).c_str());
  }
  efc::take_mujoco_warnings();
  set_counters(state, *obj);
}

template <class F>
void add(const std::string& kind, const efc_bench::BenchSpec& spec, F f) {
  benchmark::RegisterBenchmark((kind + "/" + spec.name).c_str(), f, spec)
      ->Unit(benchmark::kMillisecond)
      ->MinTime(kMinTime)
      ->Repetitions(kRepetitions)
      ->ReportAggregatesOnly(true);
}

}  // namespace

int main(int argc, char** argv) {
  efc::install_mujoco_handlers();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  for (const efc_bench::BenchSpec& spec : efc_bench::bench_specs()) {
    add("check", spec, BM_check);
    for (const char* target : {"mujoco", "urdf", "bullet"})
      add(std::string("compile_") + target, spec,
          [target](benchmark::State& st, const efc_bench::BenchSpec& sp) { BM_compile(st, sp, target); });
    add("compile_mjcf", spec, BM_compile_mjcf);
    add("write_files", spec, BM_write_files);
    add("mujoco_load", spec, BM_mujoco_load);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
