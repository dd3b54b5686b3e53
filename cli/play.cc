// efc play SPEC --profile P --duration S [--dt D] [--csv F] [--plot F.svg]
// [--render DIR] [--fps N]: the MuJoCo playback harness (harness/play.h).
#include <unistd.h>

#include "cli/commands.h"
#include "harness/play.h"

namespace efc {

int cmd_play(Report& report, const PlayArgs& args) {
  PlayOptions opts;
  int rc = kExitOk;
  std::optional<Object> obj = load_for_run(report, args.spec, args.profile, args.duration, args.dt, &opts.profile, &rc);
  if (!obj) return rc;
  opts.duration = args.duration;
  opts.dt = args.dt;
  opts.csv_path = args.csv;
  opts.render_dir = args.render;
  opts.plot_path = args.plot;
  opts.render_fps = args.fps;
  if (isatty(2) && args.duration / args.dt > 20000)
    opts.progress = [&report](const std::string& line) { report.note(line); };
  PlayLog log;
  rc = play(*obj, opts, report.diags(), &log);
  report.flush();
  if (rc == kExitOk && !args.render.empty())
    report.note("play: wrote " + std::to_string(log.frames_written) + " frames to " + args.render);
  return rc;
}

}  // namespace efc
