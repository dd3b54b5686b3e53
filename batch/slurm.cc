#include "batch/slurm.h"

#include <cctype>

#include "batch/process.h"

namespace efc::batch {

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  return out + "'";
}

bool sbatch_safe(const std::string& s) {
  for (char c : s) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == ' ' || c == '_' || c == '.' || c == '/' ||
                    c == '+' || c == ',' || c == ':' || c == '=' || c == '@' || c == '~' || c == '-';
    if (!ok) return false;
  }
  return true;
}

bool slurm_script(const std::string& efc_exe, const std::string& manifest, const std::string& dir,
                  const std::vector<std::string>& command, int tasks, const SlurmOptions& opts, std::string* script,
                  std::string* why) {
  struct Value {
    const char* option;
    std::string value;
  };
  const std::vector<Value> values = {{"--job-name", opts.job_name},
                                     {"--mem", opts.mem},
                                     {"--time", opts.time},
                                     {"--partition", opts.partition},
                                     {"--output", dir + "/logs"}};
  for (const Value& v : values)
    if (!sbatch_safe(v.value)) {
      *why =
          std::string(v.option) + " '" + v.value +
          "' holds a character an #SBATCH line cannot carry safely (only letters, digits, blanks and _ . / + , : = @ "
          "~ -)";
      return false;
    }
  std::string s = "#!/bin/bash\n";
  s += "# Written by efc batch --slurm: " + std::to_string(tasks) +
       " array tasks; task I runs shard I of the manifest's jobs.\n";
  s += "# When every task has ended: efc batch --merge DIR\n";
  s += "#SBATCH --job-name=\"" + opts.job_name + "\"\n";
  s += "#SBATCH --array=0-" + std::to_string(tasks - 1);
  if (opts.parallel > 0) s += "%" + std::to_string(opts.parallel);
  s += "\n";
  s += "#SBATCH --ntasks=1\n";
  s += "#SBATCH --cpus-per-task=" + std::to_string(opts.cpus_per_task) + "\n";
  if (!opts.mem.empty()) s += "#SBATCH --mem=\"" + opts.mem + "\"\n";
  if (!opts.time.empty()) s += "#SBATCH --time=\"" + opts.time + "\"\n";
  if (!opts.partition.empty()) s += "#SBATCH --partition=\"" + opts.partition + "\"\n";
  s += "#SBATCH --output=\"" + dir + "/logs/%A_%a.out\"\n";
  s += "set -eu\n";
  // Every path and word below is single-quoted: a manifest, a folder or an
  // argument with blanks, quotes or $(...) in its name stays one word.
  s += "exec " + shell_quote(efc_exe) + " batch " + shell_quote(manifest) + " -o " + shell_quote(dir) +
       " --shard \"${SLURM_ARRAY_TASK_ID}/${SLURM_ARRAY_TASK_COUNT}\"";
  if (opts.parallel_jobs > 0)
    s += " -j " + std::to_string(opts.parallel_jobs);
  else
    s += " -j \"${SLURM_CPUS_PER_TASK:-1}\"";
  s += " --";
  for (const std::string& w : command) s += " " + shell_quote(w);
  s += "\n";
  *script = s;
  return true;
}

bool submit(const std::string& script, std::string* job_id, std::string* why) {
  std::string out, err;
  const int rc = run_capture({"sbatch", "--parsable", script}, &out, &err);
  if (rc == 127 || rc < 0) {
    *why = "cannot run sbatch (is Slurm installed and in PATH?)" + (err.empty() ? "" : ": " + err);
    return false;
  }
  if (rc != 0) {
    *why = "sbatch failed (exit " + std::to_string(rc) + ")" + (err.empty() ? "" : ": " + err);
    while (!why->empty() && (why->back() == '\n' || why->back() == ' ')) why->pop_back();
    return false;
  }
  // --parsable prints "ID" or "ID;CLUSTER".
  std::string id;
  for (char c : out) {
    if (c == ';' || c == '\n') break;
    id += c;
  }
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
    *why = "sbatch printed no job id: '" + out + "'";
    return false;
  }
  *job_id = id;
  return true;
}

}  // namespace efc::batch
