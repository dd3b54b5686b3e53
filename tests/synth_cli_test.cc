// `efc synth` and `efc synth-suite` as a user meets them: exit codes and
// messages for bad options and specs, nothing written on failure, the
// preview, and a small suite that checks and resumes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "sequence/sequence.h"
#include "tests/efc_cli.h"

namespace {

namespace fs = std::filesystem;
using efc_test::run_efc;

const std::string kExamples = std::string(EFC_SOURCE_DIR) + "/examples/";

fs::path fresh_dir(const std::string& stem) {
  static int counter = 0;
  fs::path p = fs::temp_directory_path() / ("efc-synth-cli-" + std::to_string(getpid()) + "-" + stem + "-" +
                                            std::to_string(counter++));
  fs::remove_all(p);
  return p;
}

TEST(SynthCli, BadOptionsAreUsageErrorsAndWriteNothing) {
  const fs::path out = fresh_dir("bad");
  for (const char* opts : {"--noise loud", "--frames 0", "--fps -3", "--width 4", "--profile csv:x.csv",
                                  "--profile wobble"}) {
    auto r = run_efc("synth " + kExamples + "toaster.json -o " + out.string() + " " + std::string(opts));
    EXPECT_EQ(r.exit_code, 2) << opts << "\n" << r.err;
    EXPECT_NE(r.err.find("error[E0910]"), std::string::npos) << opts << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << opts;
  }
}

TEST(SynthCli, AWrongSpecIsLocatedAndWritesNothing) {
  const fs::path dir = fresh_dir("spec");
  fs::create_directories(dir);
  std::ofstream(dir / "bad.json") << "{\"efc\": 1, \"name\": \"x\", \"parts\": [\n  {\"name\": 3}\n]}\n";
  auto r = run_efc("synth " + (dir / "bad.json").string() + " -o " + (dir / "seq").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("bad.json:2:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "seq"));
  fs::remove_all(dir);
}

TEST(SynthCli, APartNamedHandIsRefused) {
  const fs::path dir = fresh_dir("hand");
  fs::create_directories(dir);
  std::string spec = efc_test::read_file(kExamples + "toaster.json");
  for (size_t at; (at = spec.find("\"lever\"")) != std::string::npos;) spec.replace(at, 7, "\"hand\"");
  std::ofstream(dir / "toaster.json") << spec;
  auto r = run_efc("synth " + (dir / "toaster.json").string() + " -o " + (dir / "seq").string() + " --frames 2");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("error[E1010]"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "seq"));
  fs::remove_all(dir);
}

TEST(SynthCli, WritesASequenceWithAPreviewAndReplacesOnlySequences) {
  const fs::path dir = fresh_dir("ok");
  const std::string seq = (dir / "seq").string();
  auto r = run_efc("synth " + kExamples + "toaster.json -o " + seq + " --frames 8 --width 96 --height 72 --preview");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("synth: wrote 8 frames 96x72"), std::string::npos) << r.err;
  efc::seq::Image8 sheet;
  std::string error;
  ASSERT_TRUE(efc::seq::read_png_rgb(seq + "/preview.png", &sheet, &error)) << error;
  EXPECT_EQ(sheet.width, 3 * 96);
  EXPECT_EQ(sheet.height, 72);
  EXPECT_EQ(run_efc("check-sequence " + seq).exit_code, 0);
  // Written again: the sequence is replaced (no leftovers beside it).
  r = run_efc("synth " + kExamples + "toaster.json -o " + seq + " --frames 4 --width 96 --height 72");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(seq + "/preview.png"));
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.path().filename() != "seq" ? 1 : 0;
  EXPECT_EQ(entries, 0);
  // A folder that is not a sequence is never replaced.
  const fs::path other = dir / "notes";
  fs::create_directories(other);
  std::ofstream(other / "keep.txt") << "mine";
  r = run_efc("synth " + kExamples + "toaster.json -o " + other.string() + " --frames 2 --width 32 --height 24");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(fs::exists(other / "keep.txt"));
  EXPECT_FALSE(fs::exists(other / "meta.json"));
  fs::remove_all(dir);
}

TEST(SynthCli, JsonDiagnosticsAreJsonOnly) {
  const fs::path dir = fresh_dir("json");
  auto r = run_efc("synth " + kExamples + "toaster.json -o " + (dir / "seq").string() +
                   " --frames 2 --width 32 --height 24 --diagnostics-format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(r.err);
  int n = 0;
  for (std::string line; std::getline(lines, line); ++n)
    EXPECT_TRUE(nlohmann::json::accept(line)) << line;
  EXPECT_GE(n, 1);
  fs::remove_all(dir);
}

TEST(SynthCli, ASmallSuiteIsIndexedChecksAndResumes) {
  const fs::path dir = fresh_dir("suite");
  const std::string args = "synth-suite -o " + dir.string() + " --count 3 --seed 5 --frames 6 --width 64 --height 48 --examples " + kExamples;
  auto r = run_efc(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("3 sequences made, 0 kept"), std::string::npos) << r.err;
  const nlohmann::json index = nlohmann::json::parse(efc_test::read_file(dir / "index.json"));
  ASSERT_EQ(index["sequences"].size(), 3u);
  for (const auto& s : index["sequences"]) {
    const std::string seq = (dir / s["sequence"].get<std::string>()).string();
    EXPECT_EQ(run_efc("check-sequence " + seq).exit_code, 0) << seq;
    EXPECT_EQ(run_efc("check " + (dir / s["spec"].get<std::string>()).string()).exit_code, 0);
    EXPECT_TRUE(s.contains("knobs") && s.contains("seed") && s.contains("mapping") && s.contains("effect"));
  }
  r = run_efc(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("0 sequences made, 3 kept"), std::string::npos) << r.err;
  EXPECT_EQ(run_efc("synth-suite -o " + dir.string() + " --count 0").exit_code, 2);
  fs::remove_all(dir);
}

}  // namespace
