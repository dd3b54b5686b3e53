// `efc check-sequence` as a user meets it: exit codes, located diagnostics,
// the summary of a good folder, JSON lines on request.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/render.h"
#include "tests/efc_cli.h"

namespace {

namespace fs = std::filesystem;
using efc_test::run_efc;

// A small valid sequence (meta.json and rgb/ only: the rest is optional)
// in a fresh temporary folder.
class SequenceDir {
 public:
  explicit SequenceDir(int frames) {
    static int counter = 0;
    root_ = fs::temp_directory_path() / ("efc-check-seq-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
    fs::remove_all(root_);
    fs::create_directories(path() + "/rgb");
    std::ofstream(path() + "/meta.json")
        << "{\n  \"efc_sequence\": 1,\n  \"fps\": 30,\n  \"width\": 4,\n  \"height\": 3,\n"
           "  \"intrinsics\": {\"fx\": 4, \"fy\": 4, \"cx\": 1.5, \"cy\": 1},\n  \"frames\": "
        << frames << ",\n  \"source\": \"test\"\n}\n";
    const std::vector<unsigned char> rgb(4 * 3 * 3, 128);
    for (int f = 0; f < frames; ++f) {
      char name[32];
      std::snprintf(name, sizeof name, "/rgb/%06d.png", f);
      std::string error;
      EXPECT_TRUE(efc::write_png_rgb(path() + name, rgb.data(), 4, 3, &error)) << error;
    }
  }
  ~SequenceDir() { fs::remove_all(root_); }
  std::string path() const { return (root_ / "SEQ").string(); }

 private:
  fs::path root_;
};

TEST(CheckSequenceCli, GoodSequenceExitsZeroWithASummary) {
  SequenceDir seq(3);
  const auto r = run_efc("check-sequence " + seq.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(seq.path() + ": ok, 3 frames 4x3"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("error"), std::string::npos) << r.err;
}

TEST(CheckSequenceCli, MissingFrameIsLocatedAndExitsOne) {
  SequenceDir seq(3);
  fs::remove(seq.path() + "/rgb/000002.png");
  const auto r = run_efc("check-sequence " + seq.path());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_FALSE(r.signaled);
  EXPECT_NE(r.err.find(seq.path() + "/rgb/000002.png: error[E1003]"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(": ok"), std::string::npos) << r.err;
}

TEST(CheckSequenceCli, MetaErrorsAreLocatedWithTheirLine) {
  SequenceDir seq(2);
  std::ofstream(seq.path() + "/meta.json") << "{\n  \"efc_sequence\": 1,\n  \"fps\": \"fast\"\n}\n";
  const auto r = run_efc("check-sequence " + seq.path());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find(seq.path() + "/meta.json:3:10: error[E1002]"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("at /fps"), std::string::npos) << r.err;
}

TEST(CheckSequenceCli, EveryFolderIsCheckedAndTheWorstCodeWins) {
  SequenceDir good(2), bad(2);
  fs::remove(bad.path() + "/meta.json");
  auto r = run_efc("check-sequence " + good.path() + " " + bad.path());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find(good.path() + ": ok"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(bad.path() + "/meta.json: error[E1001]"), std::string::npos) << r.err;
  // A path that is no folder at all cannot be read: exit 2, as for a spec.
  r = run_efc("check-sequence " + good.path() + "/nothing-here");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("error[E1001]"), std::string::npos) << r.err;
}

TEST(CheckSequenceCli, JsonDiagnosticsAreJsonLinesOnly) {
  SequenceDir good(2), bad(3);
  fs::remove(bad.path() + "/rgb/000002.png");
  const auto r = run_efc("check-sequence --diagnostics-format json " + good.path() + " " + bad.path());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  std::istringstream lines(r.err);
  std::string line;
  int errors = 0, notes = 0;
  while (std::getline(lines, line)) {
    const auto j = nlohmann::json::parse(line, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << "not JSON: " << line;
    if (j["severity"] == "error") {
      ++errors;
      EXPECT_EQ(j["code"], "E1003");
      EXPECT_EQ(j["file"], bad.path() + "/rgb/000002.png");
    } else {
      ++notes;
      EXPECT_NE(j["message"].get<std::string>().find(": ok, 2 frames"), std::string::npos) << line;
    }
  }
  EXPECT_EQ(errors, 1);
  EXPECT_EQ(notes, 1);
}

TEST(CheckSequenceCli, ExplainKnowsTheSequenceCodes) {
  for (const char* code : {"E1001", "E1003", "E1007", "E1009"}) {
    const auto r = run_efc(std::string("explain ") + code);
    EXPECT_EQ(r.exit_code, 0) << code << r.err;
    EXPECT_NE(r.out.find("Fix:"), std::string::npos) << code << r.out;
  }
}

}  // namespace
