// The batch folder DIR:
//   DIR/batch.json            the manifest, the command and every job (id, line, text, index);
//                             what --merge checks the shards against
//   DIR/records/ID.json       one job's result, written atomically when it ends
//   DIR/jobs/ID/              one job's output folder (its -o, and its working folder)
//   DIR/logs/ID.stdout        what the job printed on stdout
//   DIR/logs/ID.stderr        what it printed on stderr (also in its record, shortened)
//   DIR/logs/%A_%a.out        Slurm's log of each array task (--slurm)
//   DIR/results.jsonl         every job's record, one JSON object a line (or the merge)
//   DIR/results-I-of-N.jsonl  a shard's records
//   DIR/batch.sbatch          the array job script (--slurm)
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "batch/manifest.h"

namespace efc::batch {

struct Layout {
  std::string dir;  // absolute
  std::string batch_json() const { return dir + "/batch.json"; }
  std::string records() const { return dir + "/records"; }
  std::string record(const std::string& id) const { return records() + "/" + id + ".json"; }
  std::string jobs() const { return dir + "/jobs"; }
  std::string job_dir(const std::string& id) const { return jobs() + "/" + id; }
  std::string logs() const { return dir + "/logs"; }
  std::string job_stdout(const std::string& id) const { return logs() + "/" + id + ".stdout"; }
  std::string job_stderr(const std::string& id) const { return logs() + "/" + id + ".stderr"; }
  std::string script() const { return dir + "/batch.sbatch"; }
};

// Whether `dir` may be used as a batch folder: it does not exist, or is a
// folder holding nothing but what efc batch writes (the names above), so a
// batch never writes into a folder of the user's by mistake. False with *why.
bool usable_batch_dir(const std::string& dir, std::string* why);

// Creates DIR, records/, jobs/ and logs/. False with *why.
bool make_batch_dir(const Layout& layout, std::string* why);

// batch.json: {"efc_batch": 1, "manifest", "command": [...], "jobs": [{"id", "line", "index", "job"}]}.
nlohmann::ordered_json batch_info(const std::string& manifest, const std::vector<std::string>& command,
                                  const std::vector<Job>& jobs);

// The jobs' command stored in DIR/batch.json, if it is there and readable.
std::optional<nlohmann::ordered_json> read_batch_info(const Layout& layout);

}  // namespace efc::batch
