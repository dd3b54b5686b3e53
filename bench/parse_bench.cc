// Front-end throughput benchmark (bench/README.md): how fast the two spellings
// of a spec, JSON and the DSL (.efc), are read, on one large generated spec
// held in memory.
//
// The spec is bench/generate_large_spec.cc's (EFC_BENCH_PARSE_PARTS parts,
// default 6000) with every mapping parameter and every effect kind filled in
// (thresholds, hysteresis, gain and offset, cumulative initial values, fluid
// emitters, light and heat positions, airflow outlets), some mesh parts, `x-`
// keys: several MB of text. It is written once as JSON text
// (efc::dsl::print_json, the canonical layout `efc convert` writes) and once as
// DSL text (efc::dsl::print); the mesh files live in a temporary folder.
//
//   json_parse   efc::frontend::parse_positioned      text -> positioned DOM
//   json_read    efc::read_json_text                  + build_object (shape)
//   json_check   read_json_text + check_structure
//   dsl_parse    efc::dsl::parse                      text -> positioned DOM
//   dsl_read     dsl::parse + frontend::build_object  (shape)
//   dsl_check    dsl::parse + build_object + check_structure
//
// Each: 5 repetitions, median reported, throughput in MB/s (10^6 bytes of its
// own text per CPU second). At the end a side-by-side table. Before timing,
// both texts must read without an error (and should read to the same document).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "bench/generate_large_spec.h"
#include "compiler/frontend/check.h"
#include "compiler/frontend/dsl.h"
#include "compiler/frontend/json_reader.h"
#include "compiler/frontend/positioned_json.h"
#include "compiler/frontend/spec_builder.h"

namespace {

using nlohmann::json;

constexpr int kRepetitions = 5;
constexpr double kMinTime = 0.3;  // s per repetition
constexpr size_t kMaxDepth = 256;
constexpr const char* kMesh = "meshes/knob.obj";

// ------------------------------------------------------------------ the spec

// generate_large_spec plus every optional parameter and every effect kind.
json make_spec(int parts) {
  json spec = efc_bench::generate_large_spec(parts, "parse_bench");
  spec["x-generator"] = {{"program", "bench/parse_bench.cc"}, {"parts", parts}};
  std::map<std::string, const json*> by_name;
  int i = 0;
  for (json& p : spec["parts"]) {
    if (i % 7 == 3) p["x-note"] = "part " + std::to_string(i);
    // Now and then a mesh instead of a primitive (same place, the front-end
    // only checks the path).
    if (i % 97 == 50 && p["geometry"].contains("box"))
      p["geometry"] = {{"mesh", kMesh}, {"scale", {1.0, 1.0, 1.0}}};
    ++i;
  }
  for (const json& p : spec["parts"]) by_name[p["name"].get<std::string>()] = &p;
  int fn = 0;
  for (json& f : spec["functions"]) {
    const json& r = by_name.at(f["receptor"].get<std::string>())->at("joint");
    const double lo = r.contains("range") ? r["range"][0].get<double>() : 0.0;
    const double hi = r.contains("range") ? r["range"][1].get<double>() : 6.28;
    const double span = hi - lo;
    json& m = f["mapping"];
    json& e = f["effect"];
    const std::string type = m["type"];
    if (type == "binary") {
      m["threshold"] = lo + 0.5 * span;
    } else if (type == "step") {
      m["threshold"] = lo + 0.6 * span;
      m["hysteresis"] = 0.05 * span;
    } else if (type == "linear") {
      m["gain"] = 1.0 + 0.25 * (fn % 3);
      m["offset"] = 0;
    } else {  // cumulative
      m["threshold"] = lo + 0.8 * span;
      if (e["type"] != "geometry") m["initial"] = e["range"][0];
    }
    const std::string effect = e["type"];
    const json& eff = *by_name.at(f["effector"].get<std::string>());
    json center = {0.0, 0.0, 0.3};
    if (eff["geometry"].is_object())
      for (const char* kind : {"box", "cylinder", "sphere"})
        if (eff["geometry"].contains(kind) && eff["geometry"][kind].contains("center"))
          center = eff["geometry"][kind]["center"];
    if (effect == "temperature" && fn % 2 == 0) {
      // Every other heater becomes a tap: the fluid effect on the same effector.
      json fluid = {{"type", "fluid"},
                    {"range", {0, 6.5}},
                    {"emitter", {{"position", center}, {"direction", {0, 0, -1}}}},
                    {"speed", 1.1},
                    {"droplet_radius", 0.004}};
      if (m["type"] == "cumulative") m["delta"] = 1.625, m["initial"] = 0;
      e = std::move(fluid);
    } else if (effect == "temperature" || effect == "illumination") {
      e["position"] = center;
    } else if (effect == "airflow") {
      e["outlet"] = {{"position", center}, {"direction", {1, 0, 0}}};
    } else if (effect == "geometry" && fn % 4 == 1) {
      e["damping"] = 2.5;
    }
    if (fn % 11 == 0) f["x-source"] = "generated";
    ++fn;
  }
  return spec;
}

// ------------------------------------------------------------------ fixture

struct Inputs {
  std::unique_ptr<efc_bench::TempDir> dir;  // base_dir: holds the mesh
  std::string base_dir;
  std::string json_text, dsl_text;
  size_t parts = 0, functions = 0;
  std::string error;  // set when the texts do not read back cleanly
};

std::string diagnostics_text(const efc::Diagnostics& diags) {
  std::string out;
  for (size_t i = 0; i < diags.items().size() && i < 10; ++i)
    out += efc::format_text(diags.items()[i]);
  return out;
}

// The DSL path: parse, then what read_json_text does with the DOM.
std::optional<efc::Object> dsl_read(const Inputs& in, efc::Diagnostics& diags, bool check) {
  auto parsed = efc::dsl::parse(in.dsl_text, "parse_bench.efc", kMaxDepth, diags);
  if (!parsed) return std::nullopt;
  efc::Object obj;
  obj.file = "parse_bench.efc";
  obj.base_dir = in.base_dir;
  obj.positions = std::move(parsed->positions);
  efc::frontend::build_object(parsed->value, obj, efc::ReadOptions{}, diags);
  if (diags.has_errors()) return std::nullopt;
  if (check) efc::check_structure(obj, diags);
  return obj;
}

std::optional<efc::Object> json_read(const Inputs& in, efc::Diagnostics& diags, bool check) {
  auto obj = efc::read_json_text(in.json_text, "parse_bench.json", in.base_dir,
                                 efc::ReadOptions{}, diags);
  if (obj && check) efc::check_structure(*obj, diags);
  return obj;
}

const Inputs& inputs() {
  static const Inputs in = [] {
    Inputs r;
    int parts = 6000;
    if (const char* env = std::getenv("EFC_BENCH_PARSE_PARTS"); env && *env)
      parts = std::max(2, std::atoi(env));
    r.dir = std::make_unique<efc_bench::TempDir>("efc-bench-parse");
    r.base_dir = r.dir->path().string();
    std::filesystem::create_directories(r.dir->path() / "meshes");
    std::ofstream(r.dir->path() / kMesh) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const json spec = make_spec(parts);
    r.parts = spec["parts"].size();
    r.functions = spec["functions"].size();
    r.json_text = efc::dsl::print_json(spec);
    r.dsl_text = efc::dsl::print(spec);
    efc::Diagnostics jd, dd;
    auto jo = json_read(r, jd, true);
    auto dsl_doc = efc::dsl::parse(r.dsl_text, "parse_bench.efc", kMaxDepth, dd);
    auto json_doc = efc::frontend::parse_positioned(r.json_text, "parse_bench.json", kMaxDepth, jd);
    auto d_obj = dsl_read(r, dd, true);
    if (!jo || jd.has_errors())
      r.error = "the JSON text does not read cleanly:\n" + diagnostics_text(jd);
    else if (!dsl_doc || !d_obj || dd.has_errors())
      r.error = "the DSL text does not read cleanly:\n" + diagnostics_text(dd);
    // A value that does not survive the round trip is worth knowing, but the
    // timings still mean something: a warning only.
    if (r.error.empty() && (!json_doc || json_doc->value != spec))
      std::fprintf(stderr, "parse_bench: warning: the JSON text does not read back to the "
                           "generated spec\n");
    if (r.error.empty() && dsl_doc->value != spec)
      std::fprintf(stderr, "parse_bench: warning: the DSL text does not parse back to the "
                           "generated spec\n");
    return r;
  }();
  return in;
}

// ------------------------------------------------------------------ benchmarks

template <class F>
void measure(benchmark::State& state, const std::string& text, F f) {
  const Inputs& in = inputs();
  if (!in.error.empty()) return state.SkipWithError(in.error.c_str());
  for (auto _ : state) {
    efc::Diagnostics diags;
    auto result = f(in, diags);
    if (!result || diags.has_errors()) {
      state.SkipWithError("the input did not read cleanly");
      break;
    }
    benchmark::DoNotOptimize(result);
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(text.size()));
  state.counters["MB"] = static_cast<double>(text.size()) / 1e6;
  state.counters["parts"] = static_cast<double>(in.parts);
  state.counters["functions"] = static_cast<double>(in.functions);
}

void BM_json_parse(benchmark::State& state) {
  measure(state, inputs().json_text, [](const Inputs& in, efc::Diagnostics& diags) {
    return efc::frontend::parse_positioned(in.json_text, "parse_bench.json", kMaxDepth, diags);
  });
}
void BM_json_read(benchmark::State& state) {
  measure(state, inputs().json_text,
          [](const Inputs& in, efc::Diagnostics& diags) { return json_read(in, diags, false); });
}
void BM_json_check(benchmark::State& state) {
  measure(state, inputs().json_text,
          [](const Inputs& in, efc::Diagnostics& diags) { return json_read(in, diags, true); });
}
void BM_dsl_parse(benchmark::State& state) {
  measure(state, inputs().dsl_text, [](const Inputs& in, efc::Diagnostics& diags) {
    return efc::dsl::parse(in.dsl_text, "parse_bench.efc", kMaxDepth, diags);
  });
}
void BM_dsl_read(benchmark::State& state) {
  measure(state, inputs().dsl_text,
          [](const Inputs& in, efc::Diagnostics& diags) { return dsl_read(in, diags, false); });
}
void BM_dsl_check(benchmark::State& state) {
  measure(state, inputs().dsl_text,
          [](const Inputs& in, efc::Diagnostics& diags) { return dsl_read(in, diags, true); });
}

// ------------------------------------------------------------------ the table

struct Median {
  double mb_per_s = 0, ms = 0;
};

// The console reporter, also keeping each benchmark's median for the table.
class TableReporter : public benchmark::ConsoleReporter {
 public:
  explicit TableReporter(OutputOptions opts) : ConsoleReporter(opts) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.error_occurred) errors_[run.run_name.function_name] = run.error_message;
      if (run.run_type != Run::RT_Aggregate || run.aggregate_name != "median") continue;
      Median m;
      auto it = run.counters.find("bytes_per_second");
      if (it != run.counters.end()) m.mb_per_s = it->second.value / 1e6;
      m.ms = run.GetAdjustedCPUTime();  // the benchmarks report in ms
      medians_[run.run_name.function_name] = m;
    }
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, Median> medians_;
  std::map<std::string, std::string> errors_;
};

void print_table(const TableReporter& rep) {
  if (rep.medians_.empty() && rep.errors_.empty()) {
    std::printf("\nFront-end throughput: no benchmark matched the filter\n");
    return;
  }
  const Inputs& in = inputs();
  std::printf("\nFront-end throughput (median of %d repetitions, CPU time; MB = 10^6 bytes)\n",
              kRepetitions);
  std::printf("spec: %zu parts, %zu functions; JSON text %.2f MB (print_json), DSL text %.2f MB "
              "(print)\n\n",
              in.parts, in.functions, in.json_text.size() / 1e6, in.dsl_text.size() / 1e6);
  std::printf("%-34s %10s %9s %10s %9s %10s\n", "stage", "JSON MB/s", "JSON ms", "DSL MB/s",
              "DSL ms", "DSL/JSON t");
  struct Row {
    const char* label;
    const char* json_name;
    const char* dsl_name;
  };
  const Row rows[] = {{"parse (text -> positioned DOM)", "json_parse", "dsl_parse"},
                      {"+ shape (build_object)", "json_read", "dsl_read"},
                      {"+ shape + check_structure", "json_check", "dsl_check"}};
  auto cell = [&](const char* name, double Median::*field, const char* fmt) {
    auto it = rep.medians_.find(name);
    char buf[32];
    if (it == rep.medians_.end()) return std::string("-");
    std::snprintf(buf, sizeof buf, fmt, it->second.*field);
    return std::string(buf);
  };
  for (const Row& r : rows) {
    std::string ratio = "-";
    auto j = rep.medians_.find(r.json_name), d = rep.medians_.find(r.dsl_name);
    if (j != rep.medians_.end() && d != rep.medians_.end() && j->second.ms > 0) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.2f", d->second.ms / j->second.ms);
      ratio = buf;
    }
    std::printf("%-34s %10s %9s %10s %9s %10s\n", r.label,
                cell(r.json_name, &Median::mb_per_s, "%.1f").c_str(),
                cell(r.json_name, &Median::ms, "%.1f").c_str(),
                cell(r.dsl_name, &Median::mb_per_s, "%.1f").c_str(),
                cell(r.dsl_name, &Median::ms, "%.1f").c_str(), ratio.c_str());
  }
  std::printf("\nMB/s: bytes of that spelling's text per CPU second; ms: per read of the whole "
              "spec;\nDSL/JSON t: DSL time / JSON time for the same spec (< 1: the DSL is faster).\n");
  if (!in.error.empty()) std::printf("\nnot measured: %s\n", in.error.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  for (auto [name, fn] : std::vector<std::pair<const char*, void (*)(benchmark::State&)>>{
           {"json_parse", BM_json_parse},
           {"json_read", BM_json_read},
           {"json_check", BM_json_check},
           {"dsl_parse", BM_dsl_parse},
           {"dsl_read", BM_dsl_read},
           {"dsl_check", BM_dsl_check}})
    benchmark::RegisterBenchmark(name, fn)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(kMinTime)
        ->Repetitions(kRepetitions)
        ->ReportAggregatesOnly(true);
  TableReporter reporter(isatty(STDOUT_FILENO) ? benchmark::ConsoleReporter::OO_Color
                                               : benchmark::ConsoleReporter::OO_None);
  benchmark::RunSpecifiedBenchmarks(&reporter);
  print_table(reporter);
  benchmark::Shutdown();
  const bool failed = !inputs().error.empty() || !reporter.errors_.empty();
  return failed ? 1 : 0;
}
