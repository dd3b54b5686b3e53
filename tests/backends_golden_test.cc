// Golden outputs: what every registered backend generates for three examples
// that together use every effect, meshes and a chain (kitchen_faucet,
// microwave, air_conditioner), checked in under tests/golden/<target>/
// <example>.txtar, one file per target folder:
//
//   -- <path> (<N> bytes) --
//   <the file's text>
//
// Binary files (STL meshes) are recorded by size and FNV-1a hash. Fixed code
// the backends embed (the runtime, the Bullet engine, the Python glue) is not
// repeated: where an output contains a fixed file verbatim, the golden says
// [contents of <repo path>] instead, so the goldens show exactly what efc
// generates, and the test checks the fixed part is the repository's file.
//
// After an intended change, regenerate them and review the diff:
//   EFC_UPDATE_GOLDEN=1 build/tests/backends_golden_test
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "backends/backend.h"
#include "compiler/core/load.h"

namespace fs = std::filesystem;
using namespace efc;

namespace {

const char* const kExamples[] = {"kitchen_faucet", "microwave", "air_conditioner"};

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct FixedFile {
  std::string label, text;
};

// Every file a backend embeds verbatim, longest first (so a file that holds
// a shorter one is replaced whole).
std::vector<FixedFile> fixed_files() {
  const fs::path src = EFC_SOURCE_DIR;
  std::vector<FixedFile> out;
  for (const char* rel : {"runtime/efc_runtime.h", "runtime/efc_runtime.cc", "runtime/efc_profile.h",
                          "runtime/efc_profile.cc", "backends/bullet/efc_bullet_engine.h",
                          "backends/python/efc_templates.py", "backends/genesis/efc_genesis.py",
                          "backends/isaaclab/efc_isaaclab.py", "backends/omnigibson/efc_omnigibson.py"})
    if (fs::exists(src / rel)) out.push_back({rel, read_file(src / rel)});
  const fs::path amalgamated = fs::path(EFC_BINARY_DIR) / "backends/amalgamated/efc_mujoco_runtime.h";
  out.push_back({"the amalgamated runtime (backends/mujoco/amalgamate_runtime.cmake)", read_file(amalgamated)});
  std::sort(out.begin(), out.end(), [](const FixedFile& a, const FixedFile& b) { return a.text.size() > b.text.size(); });
  return out;
}

bool is_binary(const OutputFile& f) {
  return f.bytes.find('\0') != std::string::npos || f.path.size() > 4 && f.path.substr(f.path.size() - 4) == ".stl";
}

std::string fnv1a(const std::string& s) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::string render(const std::string& target, const std::string& example, std::vector<OutputFile> files,
                   const std::vector<FixedFile>& fixed) {
  std::sort(files.begin(), files.end(), [](const OutputFile& a, const OutputFile& b) { return a.path < b.path; });
  std::ostringstream o;
  o << "# efc golden: `efc compile examples/" << example << ".json --target " << target << "`\n"
    << "# Regenerate after an intended change: EFC_UPDATE_GOLDEN=1 build/tests/backends_golden_test\n";
  for (const OutputFile& f : files) {
    o << "-- " << f.path << " (" << f.bytes.size() << " bytes) --\n";
    if (is_binary(f)) {
      o << "[binary, fnv1a " << fnv1a(f.bytes) << "]\n";
      continue;
    }
    std::string text = f.bytes;
    for (const FixedFile& x : fixed) {
      if (x.text.size() < 200) continue;
      const size_t at = text.find(x.text);
      if (at != std::string::npos) text.replace(at, x.text.size(), "[contents of " + x.label + "]\n");
    }
    o << text << (text.empty() || text.back() != '\n' ? "\n[no newline at end]\n" : "");
  }
  return o.str();
}

// The first line where two texts differ, for the failure message.
std::string first_difference(const std::string& want, const std::string& got) {
  std::istringstream a(want), b(got);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool ea = !std::getline(a, la), eb = !std::getline(b, lb);
    if (ea && eb) return "(no line differs)";
    if (ea || eb || la != lb)
      return "line " + std::to_string(line) + ":\n  golden:    " + (ea ? "<end>" : la) +
             "\n  generated: " + (eb ? "<end>" : lb);
  }
}

}  // namespace

TEST(Golden, EveryBackendMatchesItsGoldenOutputs) {
  const bool update = std::getenv("EFC_UPDATE_GOLDEN") != nullptr;
  // Outputs name the spec as it was given: load it as a user in the
  // repository would, by its relative path.
  fs::current_path(EFC_SOURCE_DIR);
  const std::vector<FixedFile> fixed = fixed_files();
  int compared = 0;
  for (const Backend* backend : all_backends()) {
    for (const char* example : kExamples) {
      SCOPED_TRACE(std::string(backend->name()) + " / " + example);
      Diagnostics diags;
      auto obj = load_spec(std::string("examples/") + example + ".json", {}, diags);
      ASSERT_TRUE(obj);
      std::vector<OutputFile> files;
      ASSERT_TRUE(backend->generate(*obj, diags, &files));
      const std::string text = render(backend->name(), example, files, fixed);
      const fs::path golden = fs::path(EFC_SOURCE_DIR) / "tests/golden" / backend->name() / (std::string(example) + ".txtar");
      if (update) {
        fs::create_directories(golden.parent_path());
        std::ofstream(golden, std::ios::binary) << text;
        continue;
      }
      ASSERT_TRUE(fs::exists(golden)) << golden << " is missing; run EFC_UPDATE_GOLDEN=1 " << EFC_BINARY_DIR
                                      << "/tests/backends_golden_test";
      const std::string want = read_file(golden);
      EXPECT_EQ(want, text) << golden << " differs at " << first_difference(want, text)
                            << "\nIf the change is intended: EFC_UPDATE_GOLDEN=1 build/tests/backends_golden_test";
      ++compared;
    }
  }
  if (!update) EXPECT_EQ(compared, static_cast<int>(all_backends().size() * 3));
}

// No golden file is left over from a target or example that is gone.
TEST(Golden, EveryGoldenFileBelongsToABackendAndExample) {
  for (const auto& e : fs::recursive_directory_iterator(fs::path(EFC_SOURCE_DIR) / "tests/golden")) {
    if (!e.is_regular_file()) continue;
    const std::string target = e.path().parent_path().filename().string();
    const Backend* b = find_backend(target);
    EXPECT_TRUE(b && target == b->name()) << e.path() << ": no backend '" << target << "'";
    bool known = false;
    for (const char* example : kExamples) known |= e.path().filename() == std::string(example) + ".txtar";
    EXPECT_TRUE(known) << e.path() << ": not one of the golden examples";
  }
}
