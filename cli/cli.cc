// Argument parsing (CLI11) and dispatch to the commands (one file each).
#include <CLI/CLI.hpp>

#include <cstring>
#include <iostream>

#include "backends/backend.h"
#include "cli/commands.h"

namespace efc {
namespace {

void add_common(CLI::App* cmd, CommonOptions* common, std::string* format) {
  cmd->add_option("--diagnostics-format", *format, "text (default) or json (one JSON object per line)")
      ->check(CLI::IsMember({"text", "json"}));
  cmd->add_flag("--allow-absolute-paths", common->allow_absolute_paths,
                "let mesh paths be absolute (they may never leave the spec's folder otherwise)");
}

// What synth and synth-suite film: how many frames, how fast, how large.
void add_frame_options(CLI::App* cmd, SynthArgs* args) {
  cmd->add_option("--frames", args->frames, "frames per sequence (default 150)");
  cmd->add_option("--fps", args->fps, "frames per second (default 30)");
  cmd->add_option("--width", args->width, "image width in pixels (default 640)");
  cmd->add_option("--height", args->height, "image height in pixels (default 480)");
}

// Whether argv asks for JSON diagnostics, read before parsing: a command line
// CLI11 rejects must still be reported as JSON when JSON was asked for.
bool wants_json(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--diagnostics-format=json") == 0) return true;
    if (std::strcmp(argv[i], "--diagnostics-format") == 0 && i + 1 < argc &&
        std::strcmp(argv[i + 1], "json") == 0)
      return true;
  }
  return false;
}

}  // namespace

int run_cli(int argc, char** argv) {
  CLI::App app{"efc: a compiler for interactive 3D objects (function templates)", "efc"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "efc 0.1.0");

  CommonOptions common;
  std::string format = "text";
  // efc batch ... -- COMMAND: what follows `--` is the jobs' command, not CLI11's to parse.
  BatchArgs batch;
  argc = split_batch_command(argc, argv, &batch);

  std::vector<std::string> specs;
  bool dump_ir = false;
  CLI::App* check = app.add_subcommand("check", "read and type-check specs; write nothing");
  check->add_option("SPEC", specs, "spec files (.json or .efc)")->required();
  check->add_flag("--dump-ir", dump_ir, "print the resolved IR (every default filled) as JSON");
  add_common(check, &common, &format);

  std::vector<std::string> targets;
  std::string out_dir;
  std::string target_help = "target: all";
  for (const Backend* b : all_backends()) {
    target_help += std::string(", ") + b->name();
    for (const std::string& alias : b->aliases()) target_help += " (or " + alias + ")";
  }
  CLI::App* compile = app.add_subcommand("compile", "compile specs for simulators");
  compile->add_option("SPEC", specs, "spec files (.json or .efc)")->required();
  compile->add_option("--target,-t", targets, target_help)->required();
  compile->add_option("-o,--output", out_dir, "output folder")->required();
  add_common(compile, &common, &format);

  PlayArgs play;
  CLI::App* playc = app.add_subcommand("play", "play a spec in MuJoCo and log its templates");
  playc->add_option("SPEC", play.spec, "spec file")->required();
  playc->add_option("--profile", play.profile, "ramp, sweep, press:N, hold:V (lo/hi), csv:FILE")->required();
  playc->add_option("--duration", play.duration, "seconds")->required();
  playc->add_option("--dt", play.dt, "timestep in seconds (default 0.002)");
  playc->add_option("--csv", play.csv, "write the log: t, F.s_R, F.s_E, F.measured");
  playc->add_option("--render", play.render, "write PNG frames from an offscreen camera into DIR");
  playc->add_option("--fps", play.fps, "frames per second for --render (default 30)");
  playc->add_option("--plot", play.plot, "draw s_R, s_E and measured over time as SVG");
  add_common(playc, &common, &format);

  ParityArgs parity;
  CLI::App* parityc = app.add_subcommand(
      "parity", "run the MuJoCo harness and the compiled Bullet program; compare them per function");
  parityc->add_option("SPEC", parity.spec, "spec file")->required();
  parityc->add_option("--profile", parity.profile, "ramp, sweep, press:N, hold:V (lo/hi), csv:FILE")->required();
  parityc->add_option("--duration", parity.duration, "seconds")->required();
  parityc->add_option("--dt", parity.dt, "timestep in seconds (default 0.002)");
  parityc->add_option("--bullet-exe", parity.bullet_exe, "a built <name>_bullet program (default: build one, cached)");
  parityc->add_option("--csv-dir", parity.csv_dir, "also write mujoco.csv, bullet.csv, receptors.csv into DIR");
  add_common(parityc, &common, &format);

  ReplayArgs replay;
  CLI::App* replayc = app.add_subcommand(
      "replay", "run the function templates over a profile with no simulator (ideal joints)");
  replayc->add_option("SPEC", replay.spec, "spec file")->required();
  replayc->add_option("--profile", replay.profile, "ramp, sweep, press:N, hold:V (lo/hi), csv:FILE")->required();
  replayc->add_option("--duration", replay.duration, "seconds")->required();
  replayc->add_option("--dt", replay.dt, "timestep in seconds (default 0.002)");
  replayc->add_option("--csv", replay.csv, "write the log: t, F.s_R, F.s_E, F.measured")->required();
  add_common(replayc, &common, &format);

  SynthArgs synth;
  CLI::App* synthc = app.add_subcommand(
      "synth", "render a synthetic egocentric RGB-D sequence of SPEC being operated, with ground truth");
  synthc->add_option("SPEC", synth.spec, "spec file")->required();
  synthc->add_option("-o,--output", synth.output, "sequence folder to write")->required();
  add_frame_options(synthc, &synth);
  synthc->add_option("--profile", synth.profile, "how the hand moves each receptor: ramp, sweep (default), press:N, hold:V");
  synthc->add_option("--noise", synth.noise, "none, mild (default) or realistic");
  synthc->add_option("--seed", synth.seed, "seed of every random choice (default 0)");
  synthc->add_flag("--preview", synth.preview, "also write SEQ/preview.png: a frame, its depth and masks side by side");
  add_common(synthc, &common, &format);

  SynthSuiteArgs suite;
  CLI::App* suitec = app.add_subcommand(
      "synth-suite", "render N varied synthetic sequences (examples and generated objects) and DIR/index.json");
  suitec->add_option("-o,--output", suite.output, "suite folder to write")->required();
  suitec->add_option("--count", suite.count, "number of sequences")->required();
  suitec->add_option("--seed", suite.seed, "seed of the plan (default 0)");
  suitec->add_option("--noise", suite.noise, "none, mild or realistic for every sequence (default: drawn per sequence)");
  suitec->add_option("--examples", suite.examples, "folder of example specs to vary (default: ./examples when present)");
  add_frame_options(suitec, &suite.synth);
  add_common(suitec, &common, &format);

  std::string track, track_format;
  CLI::App* articulatec = app.add_subcommand(
      "articulate", "which joint moved a track (a hand, a handle, a part's pose): fixed, revolute or prismatic");
  articulatec->add_option("--track", track, "the track file")->required();
  articulatec->add_option("--format", track_format,
                          "xyz (x y z, or t x y z as hands.txt), pose7 (x y z qx qy qz qw), tum (t x y z qx qy qz qw)")
      ->required();
  add_common(articulatec, &common, &format);

  InferArgs infer;
  CLI::App* inferc = app.add_subcommand(
      "infer", "infer an interactive object (parts, joints, meshes, function templates) from a recording");
  inferc->add_option("SEQ", infer.sequence, "sequence folder (shared/spec/sequence.md)")->required();
  inferc->add_option("-o,--output", infer.output, "output folder: spec.json, meshes/, report.json")->required();
  inferc->add_flag("--report", infer.report, "also print the report's summary on stdout");
  inferc->add_flag("--no-hands", infer.no_hands, "ignore hands.txt (to see what the hand track buys)");
  inferc->add_option("--vlm", infer.vlm,
                     "ask a vision-language model too: an OpenAI-compatible endpoint, e.g. http://127.0.0.1:8000/v1 "
                     "(default: $EFC_VLM_ENDPOINT; off when empty)");
  inferc->add_option("--threads", infer.threads, "worker threads (default 2)");
  add_common(inferc, &common, &format);

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

  std::vector<std::string> seq_dirs;
  CLI::App* check_seq = app.add_subcommand(
      "check-sequence", "validate sequence folders (shared/spec/sequence.md)");
  check_seq->add_option("SEQ", seq_dirs, "sequence folders")->required();
  add_common(check_seq, &common, &format);

  EvalArgs evals;
  CLI::App* evalc = app.add_subcommand(
      "eval", "the EgoFun3D paper's metrics: a predicted spec against the true one, or over a list of pairs");
  evalc->add_option("--pred", evals.pred, "predicted spec (missing or broken: scored as a failure)");
  evalc->add_option("--gt", evals.gt, "true spec");
  evalc->add_option("--list", evals.list, "file of pairs: PRED GT [PRED_MASKS GT_SEQ] per line, or an efc batch's DIR/results.jsonl");
  evalc->add_option("--pred-masks", evals.pred_masks, "folder with masks/<part>/NNNNNN.png predicted");
  evalc->add_option("--gt-seq", evals.gt_seq, "true sequence (its masks/)");
  evalc->add_flag("--json", evals.json, "print one JSON object instead of tables");
  add_common(evalc, &common, &format);

  // Parsed here only for --help and usage errors; the importer program
  // (cli/import_egofun3d.cc) gets the arguments as they were given.
  std::string ego_dataset, ego_output;
  CLI::App* egofun3dc = app.add_subcommand(
      "import-egofun3d", "one sequence (with truth/) per video of an EgoFun3D-layout dataset");
  egofun3dc->add_option("DATASET", ego_dataset, "the dataset folder (holds dataset_metadata.json)")->required();
  egofun3dc->add_option("-o,--output", ego_output, "folder to write one sequence per video into")->required();
  add_common(egofun3dc, &common, &format);

  CLI::App* batchc = add_batch_command(&app, &batch);
  add_common(batchc, &common, &format);

  std::string code;
  bool list = false;
  CLI::App* explain = app.add_subcommand("explain", "explain a diagnostic code (e.g. E0203)");
  explain->add_option("CODE", code, "the code");
  explain->add_flag("--list", list, "list every code");
  add_common(explain, &common, &format);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0 || !wants_json(argc, argv)) {  // --help, --version, or text
      const int rc = app.exit(e);
      return rc == 0 ? kExitOk : kExitUsage;
    }
    common.json_diagnostics = true;
    Report report(common);
    return report.fail("E0910", e.what(), kExitUsage, "see efc --help");
  }
  common.json_diagnostics = format == "json";
  Report report(common);

  if (*check) return cmd_check(report, specs, dump_ir);
  if (*compile) return cmd_compile(report, specs, targets, out_dir);
  if (*playc) return cmd_play(report, play);
  if (*parityc) return cmd_parity(report, parity);
  if (*replayc) return cmd_replay(report, replay);
  if (*explain) return cmd_explain(report, code, list);
  if (*fmt) return cmd_fmt(report, fmt_files, fmt_check);
  if (*convert) return cmd_convert(report, convert_in, convert_out);
  if (*check_seq) return cmd_check_sequence(report, seq_dirs);
  if (*evalc) return cmd_eval(report, evals);
  if (*synthc) return cmd_synth(report, synth);
  if (*articulatec) return cmd_articulate(report, track, track_format);
  if (*egofun3dc) {
    std::vector<std::string> args;
    int k = 1;
    while (k < argc && std::strcmp(argv[k], "import-egofun3d") != 0) ++k;
    for (++k; k < argc; ++k) args.push_back(argv[k]);
    return cmd_import_egofun3d(report, args);
  }
  if (*inferc) return cmd_infer(report, infer);
  if (*suitec) return cmd_synth_suite(report, suite);
  if (*batchc) return cmd_batch(report, batch);
  return kExitUsage;
}

}  // namespace efc
