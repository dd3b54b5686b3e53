// efc batch --slurm: the same batch as a Slurm array job. Task I of N runs
//   efc batch MANIFEST -o DIR --shard I/N -j CPUS -- COMMAND...
// with the same efc program (absolute path), manifest and DIR, so a shard
// run on a cluster node is exactly a shard run here; `efc batch --merge DIR`
// then joins the shards' results.
#pragma once

#include <string>
#include <vector>

namespace efc::batch {

struct SlurmOptions {
  int tasks = 0;          // array size (0: one task per job, at most kMaxTasks)
  int parallel = 0;       // the %P throttle (0: none)
  int cpus_per_task = 1;  // also each task's -j
  std::string mem;        // --mem, e.g. 4G ("" = the cluster's default)
  std::string time;       // --time, e.g. 01:00:00
  std::string partition;  // --partition
  std::string job_name = "efc-batch";
  int parallel_jobs = 0;  // -j inside a task (0: $SLURM_CPUS_PER_TASK)
};

// Slurm's default MaxArraySize is 1001 (indices 0..1000).
constexpr int kMaxTasks = 1000;

// Single-quoted for bash: every byte kept, nothing expanded.
std::string shell_quote(const std::string& s);

// Whether `s` may stand in an #SBATCH line: sbatch reads those lines itself
// (no shell), and its file names expand '%' and treat '\' specially, so only
// letters, digits, blanks and _ . / + , : = @ ~ - are let through.
bool sbatch_safe(const std::string& s);

// The script. `tasks` is the resolved array size. False with *why when a
// value cannot go into an #SBATCH line.
bool slurm_script(const std::string& efc_exe, const std::string& manifest, const std::string& dir,
                  const std::vector<std::string>& command, int tasks, const SlurmOptions& opts, std::string* script,
                  std::string* why);

// sbatch --parsable SCRIPT: the array job's id, or false with *why.
bool submit(const std::string& script, std::string* job_id, std::string* why);

}  // namespace efc::batch
