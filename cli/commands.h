// The efc subcommands (shared/spec/cli.md), one file each. Each takes its
// parsed options and the Report every message goes through, and returns the
// process exit code.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cli/report.h"
#include "runtime/efc_profile.h"
#include "synth/synth.h"

namespace CLI {
class App;
}

namespace efc {

int run_cli(int argc, char** argv);

int cmd_check(Report& report, const std::vector<std::string>& specs, bool dump_ir);
int cmd_compile(Report& report, const std::vector<std::string>& specs,
                const std::vector<std::string>& targets, const std::string& out_dir);
int cmd_explain(Report& report, const std::string& code, bool list);
int cmd_fmt(Report& report, const std::vector<std::string>& files, bool check_only);
int cmd_convert(Report& report, const std::string& in, const std::string& out);
int cmd_check_sequence(Report& report, const std::vector<std::string>& dirs);

// efc eval (cli/eval.cc): --pred P --gt G, or --list PAIRS; masks optional.
struct EvalArgs {
  std::string pred, gt, list, pred_masks, gt_seq;
  bool json = false;
};
int cmd_eval(Report& report, const EvalArgs& args);

// efc infer (cli/infer.cc): a recording in, a spec out.
struct InferArgs {
  std::string sequence, output, vlm;
  bool report = false, no_hands = false;
  int threads = 2;
};
int cmd_infer(Report& report, const InferArgs& args);

struct PlayArgs {
  std::string spec, profile, csv, render, plot;
  double duration = 0, dt = 0.002, fps = 30;
};
int cmd_play(Report& report, const PlayArgs& args);

struct ParityArgs {
  std::string spec, profile, bullet_exe, csv_dir;
  double duration = 0, dt = 0.002;
};
int cmd_parity(Report& report, const ParityArgs& args);

struct ReplayArgs {
  std::string spec, profile, csv;
  double duration = 0, dt = 0.002;
};
int cmd_replay(Report& report, const ReplayArgs& args);

struct SynthArgs {
  std::string spec, output, profile = "sweep", noise = "mild";
  int frames = 150, width = 640, height = 480;
  double fps = 30;
  uint64_t seed = 0;
  bool preview = false;
};
int cmd_synth(Report& report, const SynthArgs& args);

struct SynthSuiteArgs {
  std::string output, noise, examples;  // noise "" = drawn per sequence
  int count = 0;
  uint64_t seed = 0;
  SynthArgs synth;  // frames, fps, width, height
};
int cmd_synth_suite(Report& report, const SynthSuiteArgs& args);
// Shared by synth and synth-suite (cli/synth.cc): 0, or the exit code after
// reporting a bad --frames, --fps, --width, --height or --noise.
int check_synth_options(Report& report, const SynthArgs& args);
// The options of one synth run (progress lines on a terminal).
synth::SynthOptions synth_options(Report& report, const SynthArgs& args);

int cmd_articulate(Report& report, const std::string& track, const std::string& format);

// efc batch (cli/batch.cc, over batch/): MANIFEST -o DIR [-j N] [--shard I/N]
// -- COMMAND..., --slurm [--submit] to write (and submit) an array job, or
// --merge DIR.
struct BatchArgs {
  std::string manifest, output, shard, merge, slurm_script;
  std::vector<std::string> command;  // what follows `--`
  bool command_given = false;
  int jobs = 0;  // -j; 0: the CPUs available
  bool retry_failed = false, slurm = false, submit = false;
  int tasks = 0, parallel = 0, cpus_per_task = 1;
  std::string mem, time, partition, job_name = "efc-batch";
};
// Takes `-- COMMAND...` off the end of `efc batch ...` (the jobs' command is
// not batch's to parse); the argc left for CLI11.
int split_batch_command(int argc, char** argv, BatchArgs* args);
CLI::App* add_batch_command(CLI::App* app, BatchArgs* args);
int cmd_batch(Report& report, const BatchArgs& args);

// efc import-egofun3d (cli/import_egofun3d.cc): execs efc-import-egofun3d,
// built next to efc, with `args` (everything after the subcommand's name).
int cmd_import_egofun3d(Report& report, const std::vector<std::string>& args);

// Shared by play, parity and replay (run_options.cc): checks --duration and
// --dt (a positive duration of at most 1e5 s, 0 < dt <= 0.1 s, dt <= duration,
// at most 50 million steps), parses --profile (reading csv:FILE) and loads the
// spec, reporting whatever is wrong. nullopt with *rc = 2 (usage, unreadable
// file) or 1 (bad CSV content, a wrong spec).
std::optional<Object> load_for_run(Report& report, const std::string& spec, const std::string& profile_text,
                                   double duration, double dt, Profile* profile, int* rc);

// Shared by check and compile: every spec loaded, every problem reported; *rc
// the worst exit code (0 when all loaded).
std::vector<Object> load_all(Report& report, const std::vector<std::string>& specs, int* rc);

}  // namespace efc
