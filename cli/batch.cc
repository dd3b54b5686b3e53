// efc batch MANIFEST -o DIR [-j N] [--shard I/N] -- COMMAND...: one efc
// command over every line of a manifest, on this machine or (--slurm) as a
// Slurm array job; efc batch --merge DIR joins the shards. The work is in
// batch/ (efc_batch); this file reads the options, reports and prints
// progress.
#include <sched.h>
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>

#include "batch/atomic_file.h"
#include "batch/command.h"
#include "batch/layout.h"
#include "batch/manifest.h"
#include "batch/merge.h"
#include "batch/record.h"
#include "batch/runner.h"
#include "batch/shard.h"
#include "batch/slurm.h"
#include "cli/commands.h"

namespace fs = std::filesystem;

namespace efc {
namespace {

const char* kBatchHelp = R"(
Runs COMMAND once per job of MANIFEST, as a separate efc process, at most -j at
a time (default: the CPUs this process may use, or $SLURM_CPUS_PER_TASK).

MANIFEST: one job a line, PATH [ARG...]. PATH is a spec or a sequence folder,
relative to the manifest's folder; the ARGs are added to that job's command.
Blank lines and '#' comments are skipped; quote with '...' or "...". With
COMMAND = NAME OPTIONS..., a job runs
  efc NAME PATH OPTIONS... ARG... -o DIR/jobs/ID  (compile, synth, infer, synth-suite, import-egofun3d)
  efc NAME PATH OPTIONS... ARG...                 (any other command)
in its own folder DIR/jobs/ID (ID = the line number and the file's name, e.g.
00003-desk_lamp), so a relative output path on a line lands there.

DIR: jobs/ID/ (outputs), logs/ID.stdout and .stderr, records/ID.json (one per
finished job, written atomically), and results.jsonl: one JSON object per job
with job (the manifest line), exit_code, seconds, peak_rss_mb, output (its
folder, relative to DIR) and diagnostics (its stderr). Running the same command
again skips every job with a complete result (--retry-failed re-runs failed
ones), so a batch that was killed or pre-empted finishes what is left. A
failing job never stops the others. SIGINT/SIGTERM are passed on to the jobs.

Shards: --shard I/N takes the jobs I, I+N, I+2N, ... (also taken from
SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT when set) and writes
DIR/results-I-of-N.jsonl; efc batch --merge DIR joins the shards into
DIR/results.jsonl (a missing shard or job is an error).

Slurm: --slurm writes DIR/batch.sbatch (or --slurm-script FILE), an array job
of --tasks tasks (default one per job, at most 1000) whose task I runs this
very command with --shard I/N; --submit also submits it with sbatch and prints
the job id. Logs: DIR/logs/%A_%a.out. When it has ended: efc batch --merge DIR,
then e.g. efc eval --list DIR/results.jsonl (infer batches over sequences).

Exit codes: 0 every job succeeded, 1 a job failed (or the manifest is wrong),
2 usage, I/O errors, or interrupted.

Examples:
  efc batch specs.txt -o out -- compile --target all
  efc batch sequences.txt -o pred -j 2 -- infer --threads 1
  efc batch sequences.txt -o pred --slurm --submit --tasks 50 --parallel 20 --cpus-per-task 2 --mem 4G -- infer
  efc batch --merge pred && efc eval --list pred/results.jsonl
)";

// The CPUs this process may run on (a cpuset or taskset counts), or Slurm's
// allocation per task.
int default_parallel() {
  if (const char* c = std::getenv("SLURM_CPUS_PER_TASK")) {
    const int n = std::atoi(c);
    if (n >= 1 && n <= 1024) return n;
  }
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1L, sysconf(_SC_NPROCESSORS_ONLN));
}

// The running program, so that the jobs (and the array tasks) run the very
// efc that was asked, wherever PATH points.
std::string self_exe() {
  char buf[PATH_MAX + 1];
  const ssize_t n = readlink("/proc/self/exe", buf, PATH_MAX);
  if (n <= 0) return {};
  return std::string(buf, static_cast<size_t>(n));
}

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string first_error_line(const std::string& diagnostics) {
  size_t start = 0;
  std::string first;
  while (start < diagnostics.size()) {
    size_t end = diagnostics.find('\n', start);
    if (end == std::string::npos) end = diagnostics.size();
    const std::string line = diagnostics.substr(start, end - start);
    start = end + 1;
    if (line.empty()) continue;
    if (first.empty()) first = line;
    if (line.find("error") != std::string::npos) return line;
  }
  return first;
}

int usage(Report& report, const std::string& message) {
  return report.fail("E0910", message, kExitUsage, "see efc batch --help");
}

int run_merge(Report& report, const BatchArgs& args) {
  batch::MergeSummary s;
  const int rc = batch::merge_shards(args.merge, report.diags(), &s);
  report.flush();
  if (rc != kExitOk) return rc;
  report.note("batch: merged " + std::to_string(s.shards) + " shards: " + std::to_string(s.jobs) + " jobs, " +
              std::to_string(s.failed) + " failed; results in " + (fs::path(args.merge) / "results.jsonl").string());
  return kExitOk;
}

// --slurm: the array job script (and --submit).
int run_slurm(Report& report, const BatchArgs& args, const batch::Layout& layout, const std::string& manifest,
              const std::vector<batch::Job>& jobs, const std::string& efc) {
  batch::SlurmOptions so;
  so.tasks = args.tasks;
  so.parallel = args.parallel;
  so.cpus_per_task = args.cpus_per_task;
  so.mem = args.mem;
  so.time = args.time;
  so.partition = args.partition;
  so.job_name = args.job_name;
  so.parallel_jobs = args.jobs;
  const int tasks = args.tasks > 0 ? args.tasks : std::min(static_cast<int>(jobs.size()), batch::kMaxTasks);
  std::string script, why;
  if (!batch::slurm_script(efc, manifest, layout.dir, args.command, tasks, so, &script, &why))
    return report.fail("E1117", why, kExitUsage, "choose simpler values (or another -o folder)");
  if (!batch::make_batch_dir(layout, &why)) return report.fail("E1105", why, kExitUsage);
  const std::string info = batch::batch_info(manifest, args.command, jobs).dump(2) + "\n";
  const std::string path = args.slurm_script.empty() ? layout.script() : fs::absolute(args.slurm_script).string();
  if (!batch::write_file_atomically(layout.batch_json(), info, &why) ||
      !batch::write_file_atomically(path, script, &why))
    return report.fail("E1105", why, kExitUsage);
  chmod(path.c_str(), 0755);
  report.note("batch: wrote " + path + ": " + std::to_string(tasks) + " array tasks over " +
              std::to_string(jobs.size()) + " jobs");
  if (!args.submit) {
    report.note("batch: submit it with: sbatch " + path + "; when it has ended: efc batch --merge " + args.output);
    return kExitOk;
  }
  std::string id;
  if (!batch::submit(path, &id, &why)) return report.fail("E1116", why, kExitUsage, "is Slurm's sbatch in PATH?");
  std::cout << id << "\n";
  std::cout.flush();
  report.note("batch: submitted array job " + id + " (" + std::to_string(tasks) + " tasks); logs in " + layout.logs() +
              "; when it has ended: efc batch --merge " + args.output);
  return kExitOk;
}

}  // namespace

int split_batch_command(int argc, char** argv, BatchArgs* args) {
  if (argc < 2 || std::strcmp(argv[1], "batch") != 0) return argc;
  for (int k = 2; k < argc; ++k)
    if (std::strcmp(argv[k], "--") == 0) {
      for (int m = k + 1; m < argc; ++m) args->command.push_back(argv[m]);
      args->command_given = true;
      return k;
    }
  return argc;
}

CLI::App* add_batch_command(CLI::App* app, BatchArgs* a) {
  CLI::App* c = app->add_subcommand(
      "batch", "run one efc command over every line of a manifest (-- COMMAND...), here or as a Slurm array job");
  c->add_option("MANIFEST", a->manifest, "one job a line: a spec or sequence path, then its own arguments");
  c->add_option("-o,--output", a->output, "the batch folder: jobs/, records/, logs/, results.jsonl");
  c->add_option("-j,--jobs", a->jobs, "jobs at a time (default: the CPUs available)");
  c->add_option("--shard", a->shard, "I/N: only the jobs I, I+N, ...; writes results-I-of-N.jsonl");
  c->add_flag("--retry-failed", a->retry_failed, "also re-run jobs whose recorded result is a failure");
  c->add_option("--merge", a->merge, "join the shards' results in DIR into DIR/results.jsonl");
  c->add_flag("--slurm", a->slurm, "write a Slurm array job script instead of running (DIR/batch.sbatch)");
  c->add_flag("--submit", a->submit, "with --slurm: submit it with sbatch and print the job id");
  c->add_option("--slurm-script", a->slurm_script, "with --slurm: write the script here instead");
  c->add_option("--tasks", a->tasks, "with --slurm: array tasks (default: one per job, at most 1000)");
  c->add_option("--parallel", a->parallel, "with --slurm: at most P tasks at a time (the array's %P)");
  c->add_option("--cpus-per-task", a->cpus_per_task, "with --slurm: CPUs per task (also its -j; default 1)");
  c->add_option("--mem", a->mem, "with --slurm: memory per task (sbatch --mem, e.g. 4G)");
  c->add_option("--time", a->time, "with --slurm: time limit per task (sbatch --time, e.g. 01:00:00)");
  c->add_option("--partition", a->partition, "with --slurm: the partition");
  c->add_option("--job-name", a->job_name, "with --slurm: the job's name (default efc-batch)");
  c->footer(kBatchHelp);
  return c;
}

int cmd_batch(Report& report, const BatchArgs& args) {
  const bool slurm_options = args.submit || !args.slurm_script.empty() || args.tasks || args.parallel ||
                             args.cpus_per_task != 1 || !args.mem.empty() || !args.time.empty() ||
                             !args.partition.empty() || args.job_name != "efc-batch";
  if (!args.merge.empty()) {
    if (!args.manifest.empty() || !args.output.empty() || args.command_given || args.slurm || slurm_options ||
        !args.shard.empty())
      return usage(report, "--merge DIR takes nothing else");
    return run_merge(report, args);
  }
  if (args.manifest.empty() || args.output.empty())
    return usage(report, "give MANIFEST -o DIR -- COMMAND..., or --merge DIR");
  const bool slurm = args.slurm || args.submit;
  if (!slurm && slurm_options) return usage(report, "--submit, --tasks, --parallel, ... go with --slurm");
  if (slurm && !args.shard.empty()) return usage(report, "--slurm sets each task's --shard itself");
  if (args.jobs < 0 || args.jobs > 1024) return usage(report, "-j must be between 1 and 1024");
  if (args.tasks < 0 || args.parallel < 0 || args.cpus_per_task < 1 || args.cpus_per_task > 1024)
    return usage(report, "--tasks and --parallel must be positive, --cpus-per-task between 1 and 1024");
  batch::OutputKind kind;
  std::string why;
  if (!batch::check_command(args.command, &kind, &why))
    return report.fail("E1103", why, kExitUsage, "efc batch MANIFEST -o DIR -- COMMAND [OPTIONS]");

  // The manifest, every line checked before anything runs or is written.
  std::vector<batch::Job> jobs;
  bool io_error = false;
  const bool read = batch::read_manifest(args.manifest, report.diags(), &jobs, &io_error) &&
                    batch::check_line_args(jobs, kind, args.manifest, report.diags());
  report.flush();
  if (!read) return io_error ? kExitUsage : kExitBadInput;

  batch::Layout layout;
  layout.dir = fs::absolute(args.output).lexically_normal().string();
  if (layout.dir.size() > 1 && layout.dir.back() == '/') layout.dir.pop_back();
  if (!batch::usable_batch_dir(layout.dir, &why))
    return report.fail("E1106", why, kExitUsage, "choose another -o folder");
  if (const auto info = batch::read_batch_info(layout))
    if ((*info)["command"] != nlohmann::ordered_json(args.command)) {
      std::string was;
      for (const auto& w : (*info)["command"]) was += " " + w.get<std::string>();
      return report.fail("E1106", "'" + args.output + "' holds a batch of another command (--" + was + ")", kExitUsage,
                         "one folder holds one command's batch: choose another -o folder");
    }
  const std::string manifest = fs::absolute(args.manifest).lexically_normal().string();
  const std::string efc = self_exe();
  if (efc.empty()) return report.fail("E1105", "cannot find the efc program (/proc/self/exe)", kExitUsage);
  if (slurm) return run_slurm(report, args, layout, manifest, jobs, efc);

  batch::Shard shard;
  if (!args.shard.empty()) {
    if (!batch::parse_shard(args.shard, &shard, &why)) return report.fail("E1104", why, kExitUsage);
  } else if (batch::shard_from_env(&shard, &why) < 0) {
    return report.fail("E1104", why, kExitUsage, "give --shard I/N");
  }
  const std::vector<batch::Job> selected = batch::select_shard(jobs, shard);

  if (!batch::make_batch_dir(layout, &why)) return report.fail("E1105", why, kExitUsage);
  if (!batch::write_file_atomically(layout.batch_json(), batch::batch_info(manifest, args.command, jobs).dump(2) + "\n",
                                    &why))
    return report.fail("E1105", why, kExitUsage);

  batch::RunOptions opts;
  opts.efc_exe = efc;
  opts.layout = layout;
  opts.command = args.command;
  opts.kind = kind;
  opts.parallel = args.jobs > 0 ? args.jobs : default_parallel();
  opts.shard = shard;
  opts.retry_failed = args.retry_failed;
  // On a terminal one line that keeps changing (and a line per failure);
  // otherwise (a log file, Slurm's output, JSON) one line per finished job.
  const bool live = isatty(2) && !report.options().json_diagnostics;
  const auto t0 = std::chrono::steady_clock::now();
  int failed_now = 0;
  auto status_line = [&](int done, int total, int running) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::string line = "[" + std::to_string(done) + "/" + std::to_string(total) + "] " + std::to_string(running) +
                       " running, " + std::to_string(failed_now) + " failed, " + fixed(s, 0) + " s";
    std::cerr << "\r\033[K" << line << std::flush;
  };
  opts.on_started = [&](const batch::Job&, int done, int total, int running) {
    if (live) status_line(done, total, running);
  };
  opts.on_finished = [&](const nlohmann::ordered_json& r, int done, int total) {
    const int code = r["exit_code"].get<int>();
    if (code != 0) ++failed_now;
    const std::string line = "[" + std::to_string(done) + "/" + std::to_string(total) + "] " +
                             r["id"].get<std::string>() + " exit " + std::to_string(code) + " in " +
                             fixed(r["seconds"].get<double>(), 1) + " s, " + fixed(r["peak_rss_mb"].get<double>(), 0) +
                             " MB";
    if (!live) {
      report.note(line);
    } else if (code != 0) {
      std::cerr << "\r\033[K";
      report.note(line);
    }
  };
  const std::string in_shard =
      shard.on ? " in shard " + std::to_string(shard.index) + "/" + std::to_string(shard.count) : std::string();
  if (!selected.empty() && !live)
    report.note("batch: " + std::to_string(selected.size()) + " jobs" + in_shard + ", -j " +
                std::to_string(opts.parallel));
  batch::RunSummary s;
  const int rc = batch::run_jobs(opts, selected, &s);
  if (live) std::cerr << "\r\033[K" << std::flush;

  for (const auto& r : s.failures)
    report.diags().error("E1110", args.manifest, r["line"].get<int>(), 0, "",
                         "job " + r["id"].get<std::string>() + " failed (exit " +
                             std::to_string(r["exit_code"].get<int>()) + ")" +
                             (r["diagnostics"].get<std::string>().empty()
                                  ? std::string()
                                  : ": " + first_error_line(r["diagnostics"].get<std::string>())),
                         "all it printed: " + (layout.logs() + "/" + r["id"].get<std::string>() + ".stderr"));
  report.flush();
  const std::string results = (fs::path(args.output) / batch::results_name(shard)).string();
  if (!s.error.empty()) report.fail("E1105", s.error, kExitUsage);
  if (s.signal) {
    const char* name = sigabbrev_np(s.signal);
    report.fail("E1111",
                "interrupted by " + (name ? "SIG" + std::string(name) : std::string("a signal")) + ": " +
                    std::to_string(s.ran + s.skipped) + " of " + std::to_string(s.total) + " jobs have results, " +
                    std::to_string(s.unfinished) + " not (nothing recorded for them)",
                kExitUsage, "run the same command again: it skips the jobs that have results");
  }
  const double rate = s.seconds > 0 ? s.ran / s.seconds : 0;
  report.note("batch: " + std::to_string(s.total) + " jobs" + in_shard + ": " + std::to_string(s.ok) + " ran ok, " +
              std::to_string(s.failed) + " failed, " + std::to_string(s.skipped) + " done before; " +
              fixed(s.seconds, 1) + " s (" + fixed(rate, 2) + " jobs/s); results in " + results);
  return rc;
}

}  // namespace efc
