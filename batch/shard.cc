#include "batch/shard.h"

#include <cstdlib>
#include <regex>

namespace efc::batch {

namespace {

// A non-negative decimal integer below 10^9 (no sign, no blanks).
bool parse_count(const std::string& s, int* out) {
  if (s.empty() || s.size() > 9) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  *out = std::atoi(s.c_str());
  return true;
}

}  // namespace

bool parse_shard(const std::string& text, Shard* shard, std::string* why) {
  const size_t slash = text.find('/');
  int i = 0, n = 0;
  if (slash == std::string::npos || !parse_count(text.substr(0, slash), &i) ||
      !parse_count(text.substr(slash + 1), &n)) {
    *why = "--shard takes I/N (two whole numbers), not '" + text + "'";
    return false;
  }
  if (n < 1 || i >= n) {
    *why = "--shard " + text + ": I must be in 0 .. N-1 and N at least 1";
    return false;
  }
  shard->on = true;
  shard->index = i;
  shard->count = n;
  return true;
}

int shard_from_env(Shard* shard, std::string* why) {
  const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
  if (!id || !count) return 0;
  const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
  int i = 0, n = 0, lo = 0;
  if (!parse_count(id, &i) || !parse_count(count, &n) || (min && !parse_count(min, &lo)) || i < lo) {
    *why = std::string("SLURM_ARRAY_TASK_ID=") + id + " and SLURM_ARRAY_TASK_COUNT=" + count + " make no shard";
    return -1;
  }
  return parse_shard(std::to_string(i - lo) + "/" + std::to_string(n), shard, why) ? 1 : -1;
}

std::vector<Job> select_shard(const std::vector<Job>& jobs, const Shard& shard) {
  if (!shard.on) return jobs;
  std::vector<Job> out;
  for (const Job& j : jobs)
    if (j.index % shard.count == shard.index) out.push_back(j);
  return out;
}

std::string results_name(const Shard& shard) {
  if (!shard.on) return "results.jsonl";
  return "results-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) + ".jsonl";
}

bool parse_results_name(const std::string& name, int* index, int* count) {
  static const std::regex re("results-([0-9]{1,9})-of-([0-9]{1,9})\\.jsonl");
  std::smatch m;
  if (!std::regex_match(name, m, re)) return false;
  *index = std::atoi(m[1].str().c_str());
  *count = std::atoi(m[2].str().c_str());
  return *count >= 1 && *index < *count;
}

}  // namespace efc::batch
