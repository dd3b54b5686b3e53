// One conformance test over every registered backend and every example
// (after Drake's common_parser_test.cc): generating is deterministic (the same
// bytes twice), every warning is located in the spec (file, line, column,
// JSON pointer), every path stays inside the target folder, and emitting
// writes nothing outside it.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "backends/backend.h"
#include "compiler/core/load.h"

namespace fs = std::filesystem;
using namespace efc;

namespace {

std::vector<std::string> example_files() {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(fs::path(EFC_SOURCE_DIR) / "examples"))
    if (e.path().extension() == ".json" || e.path().extension() == ".efc") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

std::set<std::string> tree(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) out.insert(fs::relative(e.path(), dir).string());
  return out;
}

}  // namespace

TEST(Conformance, EveryBackendOnEveryExample) {
  const std::vector<std::string> examples = example_files();
  ASSERT_GE(examples.size(), 38u);
  ASSERT_GE(all_backends().size(), 3u);
  for (const Backend* backend : all_backends()) {
    for (const std::string& file : examples) {
      SCOPED_TRACE(std::string(backend->name()) + " / " + file);
      Diagnostics load_diags;
      auto obj = load_spec(file, {}, load_diags);
      ASSERT_TRUE(obj);

      Diagnostics first, second;
      std::vector<OutputFile> a, b;
      ASSERT_TRUE(backend->generate(*obj, first, &a));
      ASSERT_TRUE(backend->generate(*obj, second, &b));
      ASSERT_FALSE(a.empty());
      ASSERT_EQ(a.size(), b.size());
      std::set<std::string> paths;
      for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].path, b[i].path);
        EXPECT_TRUE(a[i].bytes == b[i].bytes) << a[i].path << " differs between two runs";
        EXPECT_TRUE(is_contained_path(a[i].path)) << a[i].path;
        EXPECT_TRUE(paths.insert(a[i].path).second) << a[i].path << " generated twice";
      }

      ASSERT_EQ(first.items().size(), second.items().size());
      for (const Diagnostic& d : first.items()) {
        EXPECT_NE(d.severity, Severity::Error) << d.message;
        EXPECT_EQ(d.file, obj->file) << d.message;
        EXPECT_GT(d.line, 0) << d.message;
        EXPECT_GT(d.col, 0) << d.message;
        EXPECT_FALSE(d.pointer.empty()) << d.message;
        EXPECT_FALSE(d.code.empty()) << d.message;
      }

      // Emitting into a folder writes exactly the generated files there, and
      // nothing beside it.
      const fs::path parent = fs::temp_directory_path() / ("efc-conformance-" + std::to_string(getpid()));
      fs::remove_all(parent);
      const fs::path dir = parent / "target";
      fs::create_directories(dir);
      Diagnostics emit_diags;
      ASSERT_TRUE(backend->emit(*obj, dir.string(), emit_diags));
      std::set<std::string> written;
      for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) written.insert(fs::relative(e.path(), dir).string());
      EXPECT_EQ(written, paths);
      size_t outside = 0;
      for (const auto& e : fs::directory_iterator(parent)) outside += e.path().filename() != "target";
      EXPECT_EQ(outside, 0u) << "something was written beside the target folder";
      fs::remove_all(parent);
    }
  }
}

// A path that would leave the folder is refused, and nothing is written.
TEST(Conformance, WriterRefusesPathsOutsideTheFolder) {
  const fs::path dir = fs::temp_directory_path() / ("efc-contained-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "target");
  for (const char* bad : {"../escape.txt", "/tmp/abs.txt", "a/../../b.txt", "", "a//b", "./x", "a\\b", "a\nb"}) {
    SCOPED_TRACE(bad);
    EXPECT_FALSE(is_contained_path(bad));
    Diagnostics diags;
    EXPECT_FALSE(write_output_files((dir / "target").string(), {{bad, "x"}}, diags));
    EXPECT_TRUE(diags.has_errors());
  }
  EXPECT_TRUE(is_contained_path("meshes/part_0.stl"));
  EXPECT_TRUE(is_contained_path("a.b/c..d"));
  EXPECT_EQ(tree(dir), std::set<std::string>{"target"});
  fs::remove_all(dir);
}
