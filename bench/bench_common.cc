#include "bench/bench_common.h"

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>

#include "bench/generate_large_spec.h"
#include "compiler/core/load.h"
#include "compiler/diagnostics.h"

namespace fs = std::filesystem;

namespace efc_bench {

TempDir::TempDir(const std::string& prefix) {
  std::string tmpl = (fs::temp_directory_path() / (prefix + "-XXXXXX")).string();
  if (!mkdtemp(tmpl.data())) throw std::runtime_error("cannot create a temporary folder");
  path_ = tmpl;
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

const std::vector<BenchSpec>& bench_specs() {
  static std::unique_ptr<TempDir> large_dir;
  static const std::vector<BenchSpec> specs = [] {
    std::vector<BenchSpec> out;
    const char* env = std::getenv("EFC_BENCH_EXAMPLES");
    const fs::path examples = env && *env ? fs::path(env) : fs::path(EFC_SOURCE_DIR) / "examples";
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(examples, ec))
      if (entry.is_regular_file() && entry.path().extension() == ".json")
        out.push_back({entry.path().stem().string(), entry.path().string()});
    std::sort(out.begin(), out.end(),
              [](const BenchSpec& a, const BenchSpec& b) { return a.name < b.name; });
    large_dir = std::make_unique<TempDir>("efc-bench-spec");
    out.push_back({"large_200", write_large_spec(large_dir->path().string(), 200, "large_200")});
    // A copy to look at or to play (`efc play DIR/large_200.json ...`).
    if (const char* keep = std::getenv("EFC_BENCH_WRITE_SPEC"); keep && *keep)
      write_large_spec(keep, 200, "large_200");
    if (const char* only = std::getenv("EFC_BENCH_SPECS"); only && *only) {
      std::set<std::string> keep;
      std::stringstream ss(only);
      for (std::string s; std::getline(ss, s, ',');) keep.insert(s);
      out.erase(std::remove_if(out.begin(), out.end(),
                               [&](const BenchSpec& s) { return !keep.count(s.name); }),
                out.end());
    }
    return out;
  }();
  return specs;
}

std::optional<efc::Object> load(const std::string& path, std::string* error) {
  efc::Diagnostics diags;
  std::optional<efc::Object> obj = efc::load_spec(path, efc::LoadOptions{}, diags);
  if (!obj || diags.has_errors()) {
    std::ostringstream os;
    diags.print(os, false);
    *error = "cannot load " + path + ":\n" + os.str();
    return std::nullopt;
  }
  return obj;
}

bool has_fluid(const efc::Object& obj) {
  for (const efc::Function& f : obj.functions)
    if (f.effect.type == efc::EffectType::Fluid) return true;
  return false;
}

}  // namespace efc_bench
