#include "eval/batch_results.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace efc::eval {

namespace fs = std::filesystem;

bool is_batch_results(const std::string& list) {
  std::error_code ec;
  if (fs::is_directory(list, ec)) return true;
  return fs::path(list).extension() == ".jsonl";
}

bool read_batch_results(const std::string& list, Diagnostics& diags, std::vector<PairEntry>* out, bool* io_error,
                        std::string* results_file) {
  *io_error = false;
  std::error_code ec;
  const std::string path = fs::is_directory(list, ec) ? (fs::path(list) / "results.jsonl").string() : list;
  *results_file = path;
  std::ifstream in(path);
  if (fs::is_directory(path, ec) || !in) {
    *io_error = true;
    diags.error("E1022", path, 0, 0, "", "cannot read the batch results",
                "give DIR/results.jsonl of efc batch (after efc batch --merge DIR for shards)");
    return false;
  }
  const fs::path folder = fs::absolute(path, ec).parent_path();
  bool ok = true;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const nlohmann::json r = nlohmann::json::parse(line, nullptr, false);
    const bool record = !r.is_discarded() && r.is_object() && r.contains("path") && r["path"].is_string() &&
                        r.contains("output") && r["output"].is_string() && r.contains("exit_code") &&
                        r["exit_code"].is_number_integer();
    if (!record) {
      diags.error("E1118", path, n, 1, "", "not an efc batch record (job, path, exit_code, output)",
                  "merge again: efc batch --merge DIR");
      ok = false;
      continue;
    }
    PairEntry e;
    e.line = n;
    const std::string seq = r["path"].get<std::string>();
    e.gt = (fs::path(seq) / "truth" / "spec.json").string();
    const fs::path output(r["output"].get<std::string>());
    e.pred = ((output.is_absolute() ? output : folder / output) / "spec.json").lexically_normal().string();
    if (!fs::is_regular_file(e.gt, ec)) {
      diags.error("E1118", path, n, 1, "", "the job's sequence has no truth: '" + e.gt + "' does not exist",
                  "efc eval compares an infer batch over sequences with truth/ (efc synth, import-egofun3d)");
      ok = false;
      continue;
    }
    const int code = r["exit_code"].get<int>();
    if (code != 0) e.failure = "job " + r.value("id", std::string("?")) + " failed (exit " + std::to_string(code) + ")";
    out->push_back(e);
  }
  if (ok && out->empty()) {
    diags.error("E1118", path, 0, 0, "", "the results hold no jobs", "run the batch first");
    ok = false;
  }
  return ok;
}

}  // namespace efc::eval
