// Synthesis benchmark (bench/README.md): `efc synth` of a 300-frame sequence
// at 640x480 on the software renderer, per spec, end to end as the command
// does it (simulation, RGB + depth + segmentation, noise, PNGs, truth),
// written to a temporary folder.
//
//   synth_bench [--frames N] [--width W] [--height H] [--noise mild] [--json FILE]
//
// Prints, per spec: render_fps (frames over the time inside the renderer:
// RGB, depth and segmentation), fps (frames over the whole run's wall time),
// seconds, and the folder's size on disk. Specs: EFC_BENCH_SPECS (default
// kitchen_faucet, stove, desk_fan: fluid, temperature + light, airflow).
// Not a Google Benchmark program: one 300-frame run is already long and its
// own average.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "backends/common/temp_dir.h"
#include "compiler/core/load.h"
#include "synth/synth.h"
#include "bench/spec_list.h"

namespace {


}  // namespace

int main(int argc, char** argv) {
  int frames = 300, width = 640, height = 480;
  std::string noise = "mild", json_path;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--frames") frames = std::atoi(v.c_str());
    else if (a == "--width") width = std::atoi(v.c_str());
    else if (a == "--height") height = std::atoi(v.c_str());
    else if (a == "--noise") noise = v;
    else if (a == "--json") json_path = v;
    else {
      std::fprintf(stderr, "usage: synth_bench [--frames N] [--width W] [--height H] [--noise L] [--json FILE]\n");
      return 2;
    }
  }
  const std::string examples = std::string(EFC_SOURCE_DIR) + "/examples/";
  nlohmann::json results = nlohmann::json::array();
  std::printf("Synthesis: efc synth, %d frames at %dx%d, RGB + depth + segmentation, noise %s\n", frames, width,
              height, noise.c_str());
  std::printf("%-16s %12s %14s %10s %10s\n", "spec", "render fps", "end-to-end fps", "seconds", "MB");
  int status = 0;
  for (const std::string& spec : efc_bench::example_stems("kitchen_faucet,stove,desk_fan")) {
    efc::Diagnostics diags;
    const std::string path = examples + spec + ".json";
    std::optional<efc::Object> obj = efc::load_spec(path, {}, diags);
    if (!obj) {
      std::fprintf(stderr, "synth_bench: cannot load %s\n", path.c_str());
      status = 1;
      continue;
    }
    efc::synth::SynthOptions opts;
    opts.frames = frames;
    opts.width = width;
    opts.height = height;
    opts.spec_json = efc_bench::read_text(path);
    std::string error;
    int line = 0;
    bool io = false;
    efc::parse_profile("sweep", &opts.profile, &error, &line, &io);
    efc::synth::parse_noise_level(noise, &opts.knobs.noise);
    efc::TempDir dir("efc-synth-bench");
    efc::synth::SynthStats stats;
    if (efc::synth::synthesize(*obj, opts, (dir.path() / "seq").string(), diags, &stats) != 0) {
      for (const efc::Diagnostic& d : diags.items()) std::fprintf(stderr, "%s\n", efc::format_text(d).c_str());
      status = 1;
      continue;
    }
    const double render_fps = stats.frames / std::max(stats.render_seconds, 1e-9);
    const double fps = stats.frames / std::max(stats.seconds, 1e-9);
    std::printf("%-16s %12.1f %14.1f %10.2f %10.1f\n", spec.c_str(), render_fps, fps, stats.seconds,
                stats.bytes / 1e6);
    std::fflush(stdout);
    results.push_back({{"spec", spec},
                       {"frames", stats.frames},
                       {"width", width},
                       {"height", height},
                       {"noise", noise},
                       {"render_fps", render_fps},
                       {"fps", fps},
                       {"seconds", stats.seconds},
                       {"bytes", stats.bytes}});
  }
  if (!json_path.empty()) std::ofstream(json_path) << results.dump(2) << "\n";
  return status;
}
