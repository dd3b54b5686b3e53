// Runs the jobs of a batch on this machine: at most `parallel` at a time,
// each the efc program itself in its own process group, in its own folder.
// A job's record is written (atomically) when it ends, and the results file
// is rebuilt from the records, so a batch killed at any instant loses at
// most the jobs that were running, and the next run over the same DIR skips
// every job with a complete record. SIGINT, SIGTERM and SIGHUP are passed on
// to the running jobs (a second one sends SIGKILL); their jobs are not
// recorded, and run_jobs returns as interrupted.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "batch/command.h"
#include "batch/layout.h"
#include "batch/manifest.h"
#include "batch/shard.h"

namespace efc::batch {

struct RunOptions {
  std::string efc_exe;  // absolute path of the program the jobs run
  Layout layout;
  std::vector<std::string> command;
  OutputKind kind = OutputKind::Folder;
  int parallel = 1;
  Shard shard;
  bool retry_failed = false;  // also re-run jobs whose complete record says they failed
  // Called when a job ends (record written), with how many of `total` have ended.
  std::function<void(const nlohmann::ordered_json& record, int done, int total)> on_finished;
  // Called when a job starts, with the number now running.
  std::function<void(const Job& job, int done, int total, int running)> on_started;
};

struct RunSummary {
  int total = 0;                    // jobs of this run (the shard's, or all)
  int skipped = 0;                  // complete before this run
  int ran = 0, ok = 0, failed = 0;  // run now
  int signal = 0;                   // the signal that interrupted the run, or 0
  int unfinished = 0;               // jobs not recorded because of it
  double seconds = 0;
  std::vector<nlohmann::ordered_json> failures;  // every failed job's record (skipped ones too), in manifest order
  std::string error;                             // what went wrong when the results cannot be written
};

// 0 every job succeeded, 1 some failed, 2 interrupted or an I/O error
// (summary->error). `jobs` is the shard's selection.
int run_jobs(const RunOptions& opts, const std::vector<Job>& jobs, RunSummary* summary);

// Rewrites DIR/<results name> from `records` (one line each, in order).
bool write_results(const Layout& layout, const Shard& shard, const std::vector<nlohmann::ordered_json>& records,
                   std::string* error);

}  // namespace efc::batch
