// Argument parsing (CLI11) and dispatch.
#include <CLI/CLI.hpp>

#include <unistd.h>

#include <iostream>

#include "backends/backend.h"
#include "compiler/core/load.h"
#include "compiler/driver/commands.h"
#include "harness/play.h"

namespace efc {
namespace {

void add_common(CLI::App* cmd, CommonOptions* common, std::string* format) {
  cmd->add_option("--diagnostics-format", *format, "text (default) or json (one JSON object per line)")
      ->check(CLI::IsMember({"text", "json"}));
  cmd->add_flag("--allow-absolute-paths", common->allow_absolute_paths,
                "let mesh paths be absolute (they may never leave the spec's folder otherwise)");
}

}  // namespace

bool check_timing(const char* command, double duration, double dt) {
  if (!(duration > 0) || duration > 1e5) {
    std::cerr << command << ": --duration must be a positive number of seconds (at most 1e5)\n";
    return false;
  }
  if (!(dt > 0) || dt > 0.1 || dt > duration || duration / dt > 5e7) {
    std::cerr << command << ": --dt must be in (0, 0.1] seconds, not exceed --duration, and give "
                            "at most 50 million steps\n";
    return false;
  }
  return true;
}

namespace {

int cmd_play(const std::string& spec, const std::string& profile_text, double duration, double dt,
             const std::string& csv, const std::string& render, const std::string& plot, double fps,
             const CommonOptions& common) {
  Diagnostics diags;
  auto finish = [&](int rc) {
    diags.print(std::cerr, common.json_diagnostics);
    return rc;
  };
  if (!check_timing("efc play", duration, dt)) return 2;
  PlayOptions opts;
  std::string error;
  int line = 0;
  bool io = false;
  if (!parse_profile(profile_text, &opts.profile, &error, &line, &io)) {
    if (io) {
      diags.error("E0001", opts.profile.csv_path.empty() ? profile_text : opts.profile.csv_path, 0,
                  0, "", error);
      return finish(2);
    }
    if (line > 0) {
      diags.error("E0903", profile_text.substr(4), line, 1, "", error);
      return finish(1);
    }
    std::cerr << "efc play: " << error << "\n";
    return 2;
  }
  LoadOptions load_opts;
  load_opts.allow_absolute_paths = common.allow_absolute_paths;
  bool io_error = false;
  std::optional<Object> obj = load_spec(spec, load_opts, diags, &io_error);
  if (!obj) return finish(io_error ? 2 : 1);
  opts.duration = duration;
  opts.dt = dt;
  opts.csv_path = csv;
  opts.render_dir = render;
  opts.plot_path = plot;
  opts.render_fps = fps;
  opts.progress = isatty(2) && duration / dt > 20000;
  PlayLog log;
  const int rc = play(*obj, opts, diags, &log);
  if (rc == 0 && !render.empty())
    std::cerr << "play: wrote " << log.frames_written << " frames to " << render << "\n";
  return finish(rc);
}

}  // namespace

int run_cli(int argc, char** argv) {
  CLI::App app{"efc: a compiler for interactive 3D objects (function templates)", "efc"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "efc 0.1.0");

  CommonOptions common;
  std::string format = "text";

  std::vector<std::string> specs;
  bool dump_ir = false;
  CLI::App* check = app.add_subcommand("check", "read and type-check specs; write nothing");
  check->add_option("SPEC", specs, "spec files (.json or .efc)")->required();
  check->add_flag("--dump-ir", dump_ir, "print the resolved IR (every default filled) as JSON");
  add_common(check, &common, &format);

  std::vector<std::string> targets;
  std::string out_dir;
  std::string target_help = "target: all";
  for (const Backend* b : all_backends()) target_help += std::string(", ") + b->name();
  CLI::App* compile = app.add_subcommand("compile", "compile specs for simulators");
  compile->add_option("SPEC", specs, "spec files (.json or .efc)")->required();
  compile->add_option("--target,-t", targets, target_help)->required();
  compile->add_option("-o,--output", out_dir, "output folder")->required();
  add_common(compile, &common, &format);

  std::string spec, profile, csv, render, plot;
  double duration = 0, dt = 0.002, fps = 30;
  CLI::App* playc = app.add_subcommand("play", "play a spec in MuJoCo and log its templates");
  playc->add_option("SPEC", spec, "spec file")->required();
  playc->add_option("--profile", profile, "ramp, sweep, press:N, hold:V (lo/hi), csv:FILE")->required();
  playc->add_option("--duration", duration, "seconds")->required();
  playc->add_option("--dt", dt, "timestep in seconds (default 0.002)");
  playc->add_option("--csv", csv, "write the log: t, F.s_R, F.s_E, F.measured");
  playc->add_option("--render", render, "write PNG frames from an offscreen camera into DIR");
  playc->add_option("--fps", fps, "frames per second for --render (default 30)");
  playc->add_option("--plot", plot, "draw s_R, s_E and measured over time as SVG");
  add_common(playc, &common, &format);

  std::string bullet_exe, csv_dir;
  CLI::App* parity = app.add_subcommand(
      "parity", "run the MuJoCo harness and the compiled Bullet program; compare them per function");
  parity->add_option("SPEC", spec, "spec file")->required();
  parity->add_option("--profile", profile, "ramp, sweep, press:N, hold:V (lo/hi), csv:FILE")->required();
  parity->add_option("--duration", duration, "seconds")->required();
  parity->add_option("--dt", dt, "timestep in seconds (default 0.002)");
  parity->add_option("--bullet-exe", bullet_exe, "a built <name>_bullet program (default: build one, cached)");
  parity->add_option("--csv-dir", csv_dir, "also write mujoco.csv, bullet.csv, receptors.csv into DIR");
  add_common(parity, &common, &format);

  std::vector<std::string> fmt_files;
  bool fmt_check = false;
  CLI::App* fmt = app.add_subcommand("fmt", "rewrite .efc (and .json) specs in canonical form");
  fmt->add_option("FILE", fmt_files, "spec files (.efc or .json)")->required();
  fmt->add_flag("--check", fmt_check, "change nothing; exit 1 if a file would change");
  add_common(fmt, &common, &format);

  std::string convert_in, convert_out;
  CLI::App* convert = app.add_subcommand(
      "convert", "convert a spec between JSON and the DSL (by extension: .json, .efc)");
  convert->add_option("IN", convert_in, "input spec (.json or .efc)")->required();
  convert->add_option("-o,--output", convert_out, "output file (.efc or .json)")->required();
  add_common(convert, &common, &format);

  std::string code;
  bool list = false;
  CLI::App* explain = app.add_subcommand("explain", "explain a diagnostic code (e.g. E0203)");
  explain->add_option("CODE", code, "the code");
  explain->add_flag("--list", list, "list every code");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  common.json_diagnostics = format == "json";

  if (*check) return cmd_check(specs, dump_ir, common);
  if (*compile) return cmd_compile(specs, targets, out_dir, common);
  if (*playc) return cmd_play(spec, profile, duration, dt, csv, render, plot, fps, common);
  if (*parity) return cmd_parity(spec, profile, duration, dt, bullet_exe, csv_dir, common);
  if (*explain) return cmd_explain(code, list);
  if (*fmt) return cmd_fmt(fmt_files, fmt_check, common);
  if (*convert) return cmd_convert(convert_in, convert_out, common);
  return 2;
}

}  // namespace efc
