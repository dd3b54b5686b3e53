// efc synth-suite -o DIR --count N [--seed S] [--noise ...] [--examples DIR]
// [--frames N] [--fps F] [--width W] [--height H]: the benchmark set for the
// perception front-end. DIR/<name>/spec.json (and its meshes) and
// DIR/<name>/seq/ per entry of the plan (synth/suite/suite_plan.h), and
// DIR/index.json listing them. A sequence already there is kept, so an
// interrupted run goes on where it stopped.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/spec_text.h"
#include "synth/suite/suite_plan.h"
#include "synth/synth.h"

namespace fs = std::filesystem;

namespace efc {

int cmd_synth_suite(Report& report, const SynthSuiteArgs& args) {
  if (const int rc = check_synth_options(report, args.synth)) return rc;
  if (args.count < 1 || args.count > 100000)
    return report.fail("E0910", "--count must be between 1 and 100000", kExitUsage);
  const bool forced = !args.noise.empty();
  synth::NoiseLevel noise = synth::NoiseLevel::Mild;
  if (forced && !synth::parse_noise_level(args.noise, &noise))
    return report.fail("E0910", "--noise must be none, mild or realistic (not '" + args.noise + "')", kExitUsage);
  std::string examples = args.examples;
  if (examples.empty() && fs::is_directory("examples")) examples = "examples";
  if (examples.empty())
    report.note("synth-suite: no examples/ here (see --examples): generated objects only");

  std::string error;
  const std::vector<synth::SuiteEntry> plan =
      synth::plan_suite(args.count, args.seed, examples, forced ? &noise : nullptr, &error);
  if (plan.empty()) return report.fail("E0910", error.empty() ? "the suite plan is empty" : error, kExitUsage);

  std::error_code ec;
  fs::create_directories(args.output, ec);
  if (ec) return report.fail("E0900", "cannot create '" + args.output + "': " + ec.message(), kExitUsage);
  nlohmann::json sequences = nlohmann::json::array();
  const auto start = std::chrono::steady_clock::now();
  int made = 0, kept = 0;
  for (size_t i = 0; i < plan.size(); ++i) {
    const synth::SuiteEntry& e = plan[i];
    const fs::path folder = fs::path(args.output) / e.name;
    const std::string spec = (folder / "spec.json").string();
    const std::string seq = (folder / "seq").string();
    nlohmann::json line = synth::entry_to_json(e);
    line["sequence"] = e.name + "/seq";
    sequences.push_back(line);
    if (fs::exists(fs::path(seq) / "meta.json")) {  // synth writes a sequence all or nothing
      ++kept;
      continue;
    }
    fs::create_directories(folder, ec);
    for (const auto& [from, rel] : e.files_to_copy) {
      fs::create_directories((folder / rel).parent_path(), ec);
      fs::copy_file(from, folder / rel, fs::copy_options::overwrite_existing, ec);
      if (ec) return report.fail("E0900", "cannot copy '" + from + "': " + ec.message(), kExitUsage);
    }
    if (!write_atomically(spec, e.spec_json, &error)) return report.fail("E0900", error, kExitUsage);

    SynthArgs one = args.synth;
    one.spec = spec;
    one.output = seq;
    one.profile = e.profile;
    one.seed = e.seed;
    synth::SynthOptions opts = synth_options(report, one);
    opts.knobs = e.knobs;
    int rc = kExitOk;
    std::optional<Object> obj = load_for_run(report, spec, e.profile, one.frames / one.fps, opts.dt, &opts.profile, &rc);
    if (!obj) return rc;
    opts.spec_json = e.spec_json;
    rc = synth::synthesize(*obj, opts, seq, report.diags(), nullptr);
    report.flush();
    if (rc) return rc;
    ++made;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    char progress[256];
    std::snprintf(progress, sizeof progress, "synth-suite: %zu/%zu %s (%.0f s so far)", i + 1, plan.size(),
                  e.name.c_str(), elapsed);
    if (isatty(2)) report.note(progress);
  }
  const nlohmann::json index = {{"efc_synth_suite", 1},
                                {"seed", args.seed},
                                {"count", args.count},
                                {"noise", forced ? args.noise : "per sequence"},
                                {"examples", examples},
                                {"frames", args.synth.frames},
                                {"fps", args.synth.fps},
                                {"width", args.synth.width},
                                {"height", args.synth.height},
                                {"sequences", sequences}};
  if (!write_atomically((fs::path(args.output) / "index.json").string(), index.dump(2) + "\n", &error))
    return report.fail("E0900", error, kExitUsage);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  char summary[200];
  std::snprintf(summary, sizeof summary, "synth-suite: %d sequences made, %d kept, in %.1f s -> %s/index.json", made,
                kept, elapsed, args.output.c_str());
  report.note(summary);
  return kExitOk;
}

}  // namespace efc
