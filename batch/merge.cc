#include "batch/merge.h"

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "batch/atomic_file.h"
#include "batch/layout.h"
#include "batch/record.h"
#include "batch/shard.h"

namespace efc::batch {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

int merge_shards(const std::string& dir_in, Diagnostics& diags, MergeSummary* summary) {
  *summary = MergeSummary{};
  std::error_code ec;
  Layout layout;
  layout.dir = fs::absolute(dir_in, ec).lexically_normal().string();
  if (!fs::is_directory(layout.dir, ec)) {
    diags.error("E1115", dir_in, 0, 0, "", "not a folder: nothing to merge", "give the -o folder of the shards");
    return 2;
  }
  const std::optional<json> info = read_batch_info(layout);
  if (!info) {
    diags.error("E1115", layout.batch_json(), 0, 0, "", "missing or unreadable: it lists the jobs the shards must hold",
                "efc batch --slurm and every shard write it; is this the shards' -o folder?");
    return 2;
  }

  // The shard files, by N.
  std::map<int, std::set<int>> by_count;
  for (const auto& e : fs::directory_iterator(layout.dir, ec)) {
    int i = 0, n = 0;
    if (parse_results_name(e.path().filename().string(), &i, &n)) by_count[n].insert(i);
  }
  if (by_count.empty()) {
    diags.error("E1112", dir_in, 0, 0, "", "no shard results (results-I-of-N.jsonl) to merge",
                "run the shards first: efc batch MANIFEST -o DIR --shard I/N -- COMMAND (or --slurm --submit)");
    return 1;
  }
  if (by_count.size() > 1) {
    std::string counts;
    for (const auto& [n, s] : by_count) counts += (counts.empty() ? "" : ", ") + std::to_string(n);
    diags.error("E1114", dir_in, 0, 0, "", "shard results of different shard counts N (" + counts + ")",
                "remove the results-I-of-N.jsonl files of the old split and merge again");
    return 1;
  }
  const int count = by_count.begin()->first;
  const std::string manifest = (*info).value("manifest", std::string("MANIFEST"));
  std::string command;
  for (const auto& w : (*info)["command"]) command += " " + w.get<std::string>();
  bool ok = true;
  std::vector<std::map<std::string, json>> shard_records(count);
  std::vector<bool> missing(count, false);
  for (int i = 0; i < count; ++i) {
    const Shard shard{true, i, count};
    const std::string path = layout.dir + "/" + results_name(shard);
    std::string text;
    if (!by_count.begin()->second.count(i) || !read_whole_file(path, &text)) {
      diags.error("E1112", path, 0, 0, "",
                  "shard " + std::to_string(i) + " of " + std::to_string(count) +
                      " has no results: its task did not run or did not get to its end",
                  "run it again: efc batch " + manifest + " -o " + dir_in + " --shard " + std::to_string(i) + "/" +
                      std::to_string(count) + " --" + command);
      ok = false;
      missing[i] = true;
      continue;
    }
    ++summary->shards;
    size_t start = 0;
    for (int line = 1; start < text.size(); ++line) {
      size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      const std::string body = text.substr(start, end - start);
      start = end + 1;
      if (body.find_first_not_of(" \t\r") == std::string::npos) continue;
      json r = json::parse(body, nullptr, false);
      if (r.is_discarded() || !record_complete(r)) {
        diags.error("E1114", path, line, 1, "", "not a complete job record",
                    "the shard's results are rebuilt from DIR/records/ by running the shard again");
        ok = false;
        continue;
      }
      const std::string id = r["id"].get<std::string>();
      shard_records[i][id] = std::move(r);
    }
  }

  // Every job of batch.json, from its own shard.
  std::vector<json> merged;
  for (const auto& job : (*info)["jobs"]) {
    const int index = job["index"].get<int>();
    const int shard = index % count;
    const std::string id = job["id"].get<std::string>();
    if (missing[shard]) continue;  // reported once, for the shard
    const auto it = shard_records[shard].find(id);
    if (it == shard_records[shard].end() || it->second["job"] != job["job"]) {
      diags.error("E1113", manifest, job["line"].get<int>(), 0, "",
                  "job " + id + " has no result in shard " + std::to_string(shard) + " of " + std::to_string(count) +
                      " (results-" + std::to_string(shard) + "-of-" + std::to_string(count) + ".jsonl)",
                  "run that shard again; it skips the jobs it has done");
      ok = false;
      continue;
    }
    merged.push_back(it->second);
  }
  if (!ok) return 1;
  std::string text;
  for (const json& r : merged) {
    text += record_line(r) + "\n";
    if (r["exit_code"].get<int>() != 0) ++summary->failed;
  }
  summary->jobs = static_cast<int>(merged.size());
  std::string error;
  if (!write_file_atomically(layout.dir + "/results.jsonl", text, &error)) {
    diags.error("E1105", layout.dir + "/results.jsonl", 0, 0, "", error);
    return 2;
  }
  return 0;
}

}  // namespace efc::batch
