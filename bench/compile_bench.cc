// Compile-time benchmark (bench/README.md). For every examples/*.json and the
// generated 200-part spec:
//   check/<spec>           efc::load_spec = read + resolve + check (`efc check`)
//   compile_mujoco/<spec>  load_spec + the mujoco backend's emit into an empty
//                          folder (`efc compile --target mujoco`, minus the CLI)
//   generate_mujoco/<spec> load_spec + generate_mujoco_target: the same output
//                          made in memory, not written: efc's own work
//   write_files/<spec>     writing those files (write_output_files, as emit
//                          does), their bytes already in memory: the file
//                          system's share of compile_mujoco
//   mujoco_load/<spec>     mj_loadXML of the emitted XML: what MuJoCo itself
//                          takes to load the result (compile should be well under)
//   emit_<target>/<spec>   every registered target's Backend::generate on the
//                          loaded object: the emission alone, per target, in
//                          memory (no reading, no checking, no files)
// Each is repeated 5 times and reported as mean / median / stddev (ms).
#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <filesystem>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "backends/mujoco/mujoco_backend.h"
#include "backends/common/output_file.h"
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

// Everything `efc compile --target mujoco` computes, without the file system:
// reading, checking, and generating every output file in memory.
void BM_generate(benchmark::State& state, const efc_bench::BenchSpec& spec) {
  std::string error;
  const auto obj = efc_bench::load(spec.path, &error);
  if (!obj) return state.SkipWithError(error.c_str());
  for (auto _ : state) {
    efc::Diagnostics diags;
    auto o = efc::load_spec(spec.path, efc::LoadOptions{}, diags);
    std::vector<efc::OutputFile> files;
    if (!o || !efc::generate_mujoco_target(*o, diags, &files)) {
      state.SkipWithError(("generate failed for " + spec.path).c_str());
      break;
    }
    benchmark::DoNotOptimize(files.data());
  }
  set_counters(state, *obj);
}

// Writing the files `efc compile --target mujoco` writes for this spec (their
// bytes already in memory; the same write_output_files as emit) into an empty
// folder: what the file system charges for the output alone, which any tool
// producing these files would pay.
void BM_write_files(benchmark::State& state, const efc_bench::BenchSpec& spec) {
  std::string error;
  const auto obj = efc_bench::load(spec.path, &error);
  if (!obj) return state.SkipWithError(error.c_str());
  efc::Diagnostics diags;
  std::vector<efc::OutputFile> files;
  if (!efc::generate_mujoco_target(*obj, diags, &files))
    return state.SkipWithError(("generate failed for " + spec.path).c_str());
  efc_bench::TempDir tmp("efc-bench-files");
  const std::string out = (tmp.path() / "mujoco").string();
  for (auto _ : state) {
    std::error_code ec;
    fs::create_directory(out, ec);
    if (!efc::write_output_files(out, files, diags)) {
      state.SkipWithError(("cannot write into " + out).c_str());
      break;
    }
    state.PauseTiming();
    fs::remove_all(out, ec);
    state.ResumeTiming();
  }
  state.counters["files"] = static_cast<double>(files.size());
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

// One target's emission: generate its whole folder in memory from the
// loaded, checked object.
void BM_emit(benchmark::State& state, const efc_bench::BenchSpec& spec, const efc::Backend* backend) {
  std::string error;
  const auto obj = efc_bench::load(spec.path, &error);
  if (!obj) return state.SkipWithError(error.c_str());
  size_t bytes = 0, count = 0;
  for (auto _ : state) {
    efc::Diagnostics diags;
    std::vector<efc::OutputFile> files;
    if (!backend->generate(*obj, diags, &files)) {
      state.SkipWithError(("generate failed for " + spec.path).c_str());
      break;
    }
    count = files.size();
    bytes = 0;
    for (const efc::OutputFile& f : files) bytes += f.bytes.size();
    benchmark::DoNotOptimize(files.data());
  }
  state.counters["files"] = static_cast<double>(count);
  state.counters["bytes"] = static_cast<double>(bytes);
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
    add("generate_mujoco", spec, BM_generate);
    add("write_files", spec, BM_write_files);
    add("mujoco_load", spec, BM_mujoco_load);
    for (const efc::Backend* backend : efc::all_backends())
      add(std::string("emit_") + backend->name(), spec,
          [backend](benchmark::State& st, const efc_bench::BenchSpec& sp) { BM_emit(st, sp, backend); });
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
