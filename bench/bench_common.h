// Shared by the benchmarks: which specs to measure, temporary folders, and
// loading a spec with its diagnostics turned into an error message.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "compiler/ir.h"

namespace efc_bench {

// A temporary folder, removed with everything in it when destroyed.
class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "efc-bench");
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

struct BenchSpec {
  std::string name;  // file stem: "desk_lamp", "large_200"
  std::string path;
};

// Every examples/*.json (sorted; $EFC_BENCH_EXAMPLES overrides the folder)
// followed by the generated 200-part spec, written once per process into a
// temporary folder that lives until exit. $EFC_BENCH_SPECS (comma-separated
// stems) keeps only those; $EFC_BENCH_WRITE_SPEC=DIR also writes
// DIR/large_200.json.
const std::vector<BenchSpec>& bench_specs();

// efc::load_spec; on failure, nullopt and *error holds the diagnostics.
std::optional<efc::Object> load(const std::string& path, std::string* error);

bool has_fluid(const efc::Object& obj);

}  // namespace efc_bench
