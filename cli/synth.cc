// efc synth SPEC -o SEQ [--frames N] [--fps F] [--width W] [--height H]
// [--profile P] [--noise none|mild|realistic] [--seed S] [--preview]:
// a synthetic egocentric RGB-D sequence (synth/synth.h).
#include <unistd.h>

#include <cstdio>

#include "cli/commands.h"
#include "cli/spec_text.h"
#include "synth/image/rng.h"
#include "synth/synth.h"

namespace efc {

int check_synth_options(Report& report, const SynthArgs& args) {
  if (args.frames < 1 || args.frames > 100000)
    return report.fail("E0910", "--frames must be between 1 and 100000", kExitUsage);
  if (!(args.fps > 0) || args.fps > 240) return report.fail("E0910", "--fps must be in (0, 240]", kExitUsage);
  if (args.width < 16 || args.width > 4096 || args.height < 16 || args.height > 4096)
    return report.fail("E0910", "--width and --height must be between 16 and 4096 pixels", kExitUsage);
  synth::NoiseLevel level;
  if (!synth::parse_noise_level(args.noise, &level))
    return report.fail("E0910", "--noise must be none, mild or realistic (not '" + args.noise + "')", kExitUsage);
  return kExitOk;
}

synth::SynthOptions synth_options(Report& report, const SynthArgs& args) {
  synth::SynthOptions opts;
  opts.frames = args.frames;
  opts.fps = args.fps;
  opts.width = args.width;
  opts.height = args.height;
  opts.seed = args.seed;
  opts.preview = args.preview;
  synth::parse_noise_level(args.noise, &opts.knobs.noise);
  // Where the object stands comes from the seed, so the world frame is never
  // the object's own (an estimator must find the object's pose).
  synth::Rng place(synth::stream_seed(args.seed, 0x706c616365));  // "place"
  opts.knobs.object_yaw = place.uniform(-0.5, 0.5);
  opts.knobs.object_x = place.uniform(-0.1, 0.1);
  opts.knobs.object_y = place.uniform(-0.1, 0.1);
  if (isatty(2)) opts.progress = [&report](const std::string& line) { report.note(line); };
  return opts;
}

int cmd_synth(Report& report, const SynthArgs& args) {
  if (const int rc = check_synth_options(report, args)) return rc;
  if (args.profile.rfind("csv:", 0) == 0)
    return report.fail("E0910", "--profile csv:FILE is not offered by synth: the hand's schedule sets the times",
                       kExitUsage, "use ramp, sweep, press:N or hold:V");
  synth::SynthOptions opts = synth_options(report, args);
  int rc = kExitOk;
  std::optional<Object> obj =
      load_for_run(report, args.spec, args.profile, args.frames / args.fps, opts.dt, &opts.profile, &rc);
  if (!obj) return rc;
  std::optional<SpecDocument> doc = read_document_reported(report, args.spec, &rc);
  if (!doc) return rc;
  opts.spec_json = render_document(*doc, false);
  synth::SynthStats stats;
  rc = synth::synthesize(*obj, opts, args.output, report.diags(), &stats);
  report.flush();
  if (rc == kExitOk) {
    char line[200];
    std::snprintf(line, sizeof line,
                  "synth: wrote %d frames %dx%d to %s in %.1f s (%.1f frames/s; rendering %.1f s; %.1f MB)",
                  stats.frames, args.width, args.height, args.output.c_str(), stats.seconds,
                  stats.frames / std::max(stats.seconds, 1e-9), stats.render_seconds, stats.bytes / 1e6);
    report.note(line);
  }
  return rc;
}

}  // namespace efc
