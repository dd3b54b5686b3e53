#include "batch/layout.h"

#include <filesystem>
#include <set>

#include "batch/atomic_file.h"
#include "batch/shard.h"

namespace efc::batch {

namespace fs = std::filesystem;

bool usable_batch_dir(const std::string& dir, std::string* why) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return true;
  if (!fs::is_directory(dir, ec)) {
    *why = "'" + dir + "' exists and is not a folder";
    return false;
  }
  static const std::set<std::string> ours = {"batch.json", "records", "jobs", "logs", "results.jsonl", "batch.sbatch"};
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    int i = 0, n = 0;
    const bool script = name.size() > 7 && name.compare(name.size() - 7, 7, ".sbatch") == 0;  // --slurm-script
    if (ours.count(name) || script || parse_results_name(name, &i, &n) || name.rfind(kTempPrefix, 0) == 0) continue;
    *why = "'" + dir + "' holds '" + name + "', which efc batch did not write: it is not a batch folder";
    return false;
  }
  if (ec) {
    *why = "cannot list '" + dir + "': " + ec.message();
    return false;
  }
  return true;
}

bool make_batch_dir(const Layout& layout, std::string* why) {
  for (const std::string& d : {layout.dir, layout.records(), layout.jobs(), layout.logs()}) {
    std::error_code ec;
    fs::create_directories(d, ec);
    if (ec || !fs::is_directory(d, ec)) {
      *why = "cannot create '" + d + "'" + (ec ? ": " + ec.message() : "");
      return false;
    }
  }
  return true;
}

nlohmann::ordered_json batch_info(const std::string& manifest, const std::vector<std::string>& command,
                                  const std::vector<Job>& jobs) {
  nlohmann::ordered_json info = {{"efc_batch", 1}, {"manifest", manifest}, {"command", command}};
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const Job& j : jobs)
    list.push_back({{"id", j.id}, {"line", j.line}, {"index", j.index}, {"job", j.text}, {"path", j.path}});
  info["jobs"] = std::move(list);
  return info;
}

std::optional<nlohmann::ordered_json> read_batch_info(const Layout& layout) {
  std::string text;
  if (!read_whole_file(layout.batch_json(), &text)) return std::nullopt;
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("command") || !j["command"].is_array() || !j.contains("jobs") ||
      !j["jobs"].is_array())
    return std::nullopt;
  for (const auto& job : j["jobs"])
    if (!job.is_object() || !job.contains("id") || !job["id"].is_string() || !job.contains("index") ||
        !job["index"].is_number_integer() || !job.contains("job") || !job["job"].is_string() || !job.contains("line") ||
        !job["line"].is_number_integer())
      return std::nullopt;
  return j;
}

}  // namespace efc::batch
