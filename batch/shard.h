// --shard I/N: the jobs whose index (0-based position in the manifest) is
// I modulo N, so N array tasks split a manifest evenly without talking to
// each other, and a job's shard depends only on the manifest.
#pragma once

#include <string>
#include <vector>

#include "batch/manifest.h"

namespace efc::batch {

struct Shard {
  bool on = false;  // false: every job, results.jsonl
  int index = 0, count = 1;
};

// "I/N" with 0 <= I < N; false with *why.
bool parse_shard(const std::string& text, Shard* shard, std::string* why);

// From SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT (I = ID minus
// SLURM_ARRAY_TASK_MIN, which is 0 for the arrays efc batch --slurm writes).
// Returns 0 when they are not set, 1 when *shard was set, -1 with *why when
// they are set but make no shard.
int shard_from_env(Shard* shard, std::string* why);

std::vector<Job> select_shard(const std::vector<Job>& jobs, const Shard& shard);

// "results.jsonl" or "results-I-of-N.jsonl".
std::string results_name(const Shard& shard);

// Parses "results-I-of-N.jsonl"; false for any other name.
bool parse_results_name(const std::string& name, int* index, int* count);

}  // namespace efc::batch
