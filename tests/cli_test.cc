// The efc command line as a user meets it: exit codes, located diagnostics,
// all-or-nothing output, and no crash on any malformed file.
#include <gtest/gtest.h>

#include "tests/efc_cli.h"
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>
#include "tests/process_temp_dir.h"

namespace fs = std::filesystem;

namespace {

const fs::path kSource = EFC_SOURCE_DIR;

using Result = efc_test::CliResult;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path scratch(const std::string& name) {
  static const efc_test::ProcessTempDir root("efc-cli-");
  fs::path p = root.path() / name;
  fs::remove_all(p);
  fs::create_directories(p.parent_path());
  return p;
}

Result efc(const std::string& args) { return efc_test::run_efc(args); }

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

struct Expectation {
  std::string code;
  int line;
};

std::vector<Expectation> expectations_for(const fs::path& file) {
  std::vector<Expectation> out;
  const nlohmann::json table = nlohmann::json::parse(slurp(kSource / "tests/specs/bad/expectations.json"));
  nlohmann::json list;
  if (table.contains(file.filename().string())) {
    list = table[file.filename().string()];
  } else {
    const nlohmann::json doc = nlohmann::json::parse(slurp(file), nullptr, false);
    if (doc.is_object() && doc.contains("x-expect")) list = doc["x-expect"];
  }
  for (const auto& e : list) out.push_back({e["code"], e["line"]});
  return out;
}

}  // namespace

TEST(Cli, EveryBadSpecFailsWithItsCodeAtItsLine) {
  int files = 0;
  for (const auto& e : fs::directory_iterator(kSource / "tests/specs/bad")) {
    if (e.path().filename() == "expectations.json" || e.path().extension() != ".json") continue;
    SCOPED_TRACE(e.path().filename().string());
    const std::vector<Expectation> want = expectations_for(e.path());
    ASSERT_FALSE(want.empty()) << "every bad spec states its expected diagnostics";
    const Result r = efc("check " + q(e.path()));
    EXPECT_FALSE(r.signaled);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    for (const Expectation& x : want) {
      const std::string located = e.path().string() + ":" + std::to_string(x.line) + ":";
      bool found = false;
      std::istringstream lines(r.err);
      for (std::string line; std::getline(lines, line);)
        found |= line.rfind(located, 0) == 0 && line.find("error[" + x.code + "]") != std::string::npos;
      EXPECT_TRUE(found) << "expected " << x.code << " at line " << x.line << ", got:\n" << r.err;
    }
    ++files;
  }
  EXPECT_GT(files, 30);
}

TEST(Cli, BadSpecCompilesToNothing) {
  const fs::path out = scratch("bad-out");
  int files = 0;
  for (const auto& e : fs::directory_iterator(kSource / "tests/specs/bad")) {
    if (e.path().filename() == "expectations.json") continue;
    const Result r = efc("compile " + q(e.path()) + " --target all -o " + q(out));
    EXPECT_FALSE(r.signaled) << e.path();
    EXPECT_EQ(r.exit_code, 1) << e.path() << r.err;
    EXPECT_FALSE(fs::exists(out)) << e.path();
    ++files;
  }
  EXPECT_GT(files, 30);
  // Nothing staged is left behind either.
  for (const auto& e : fs::directory_iterator(out.parent_path()))
    EXPECT_EQ(e.path().filename().string().find(".efc-staging"), std::string::npos);
}

TEST(Cli, OneBadSpecAmongGoodOnesChangesNothing) {
  const fs::path out = scratch("mixed-out");
  fs::create_directories(out);
  std::ofstream(out / "keep.txt") << "user file";
  const Result r = efc("compile " + q(kSource / "examples/desk_lamp.json") + " " +
                       q(kSource / "tests/specs/bad/own_parent.json") + " --target mujoco -o " + q(out));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 1);
}

TEST(Cli, DeepNestingIsAnErrorNotACrash) {
  const fs::path file = scratch("deep.json");
  {
    std::ofstream f(file);
    f << "{\"efc\": 1, \"name\": \"deep\", \"x-deep\": ";
    for (int i = 0; i < 100000; ++i) f << '[';
    for (int i = 0; i < 100000; ++i) f << ']';
    f << "}";
  }
  const Result r = efc("check " + q(file));
  EXPECT_FALSE(r.signaled);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("error["), std::string::npos);
}

TEST(Cli, MissingFileIsExitTwo) {
  const Result r = efc("check /nonexistent/spec.json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error[E0001]"), std::string::npos) << r.err;
}

TEST(Cli, UsageErrorsAreExitTwo) {
  EXPECT_EQ(efc("").exit_code, 2);
  EXPECT_EQ(efc("frobnicate").exit_code, 2);
  EXPECT_EQ(efc("compile " + q(kSource / "examples/desk_lamp.json") + " --target nosuch -o /tmp/x").exit_code, 2);
  EXPECT_EQ(efc("play " + q(kSource / "examples/desk_lamp.json") + " --profile wobble --duration 1").exit_code, 2);
  EXPECT_EQ(efc("--help").exit_code, 0);
}

TEST(Cli, ExplainDocumentsCodes) {
  Result r = efc("explain E0203");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("E0203"), std::string::npos);
  EXPECT_GT(r.out.size(), 100u);
  EXPECT_EQ(efc("explain E9999").exit_code, 2);
  r = efc("explain --list");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("E0001"), std::string::npos);
}

TEST(Cli, JsonDiagnosticsAreJsonLines) {
  const Result r = efc("check --diagnostics-format json " + q(kSource / "tests/specs/bad/own_parent.json"));
  EXPECT_EQ(r.exit_code, 1);
  std::istringstream lines(r.err);
  int n = 0;
  for (std::string line; std::getline(lines, line);) {
    const auto j = nlohmann::json::parse(line);
    EXPECT_EQ(j["severity"], "error");
    EXPECT_TRUE(j.contains("code") && j.contains("line") && j.contains("column") && j.contains("pointer"));
    ++n;
  }
  EXPECT_GE(n, 1);
}

// With --diagnostics-format json every line the program writes to stderr is a
// JSON object: warnings, progress notes, the program's own errors (an unknown
// target, a command line CLI11 rejects, an unusable --dt), for every command.
TEST(Cli, JsonDiagnosticsFormatPrintsOnlyJson) {
  const fs::path out = fs::temp_directory_path() / ("efc-json-only-" + std::to_string(getpid()));
  fs::remove_all(out);
  const std::string toaster = q(kSource / "examples/toaster.json");
  const std::vector<std::pair<std::string, int>> runs = {
      {"compile " + toaster + " --target all -o " + q(out) + " --diagnostics-format json", 0},
      {"compile " + toaster + " --target nope -o " + q(out) + " --diagnostics-format json", 2},
      {"compile " + toaster + " --diagnostics-format=json", 2},
      {"play " + toaster + " --profile ramp --duration 1 --dt 5 --diagnostics-format json", 2},
      {"replay " + toaster + " --profile wobble --duration 1 --csv x.csv --diagnostics-format json", 2},
      {"explain E9999 --diagnostics-format json", 2}};
  for (const auto& [args, code] : runs) {
    SCOPED_TRACE(args);
    const Result r = efc(args);
    EXPECT_EQ(r.exit_code, code) << r.err;
    std::istringstream lines(r.err);
    int n = 0;
    for (std::string line; std::getline(lines, line); ++n) {
      const auto j = nlohmann::json::parse(line, nullptr, false);
      ASSERT_FALSE(j.is_discarded()) << "not JSON: " << line;
      EXPECT_TRUE(j.contains("severity") && j.contains("message")) << line;
    }
    EXPECT_GE(n, 1);
  }
  fs::remove_all(out);
}

TEST(Cli, DumpIrShowsFilledDefaults) {
  const Result r = efc("check --dump-ir " + q(kSource / "examples/desk_lamp.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ir = nlohmann::json::parse(r.out);
  ASSERT_FALSE(ir["functions"].empty());
  size_t defaulted = 0;
  for (const auto& f : ir["functions"]) {
    if (f["mapping"]["type"] != "linear") {
      EXPECT_TRUE(f["mapping"].contains("threshold"));
    }
    defaulted += f["mapping"]["defaulted"].size() + f["effect"]["defaulted"].size();
  }
  EXPECT_GT(defaulted, 0u) << "the lamp leaves some parameters to the spec's rules";
  EXPECT_GT(ir["parts"][0]["mass"].get<double>(), 0);
}

TEST(Cli, CompileWritesTheMujocoTarget) {
  const fs::path out = scratch("good-out");
  const Result r = efc("compile " + q(kSource / "examples/desk_lamp.json") + " --target mujoco -o " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "mujoco/desk_lamp.xml"));
  EXPECT_TRUE(fs::exists(out / "mujoco/desk_lamp_callbacks.cc"));
  EXPECT_TRUE(fs::exists(out / "mujoco/README.md"));
}

TEST(Cli, PlayWritesTheCsvContract) {
  const fs::path csv = scratch("lamp.csv"), svg = scratch("lamp.svg");
  const Result r = efc("play " + q(kSource / "examples/desk_lamp.json") +
                       " --profile press:2 --duration 2 --csv " + q(csv) + " --plot " + q(svg));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(csv);
  std::string header, first;
  std::getline(in, header);
  std::getline(in, first);
  EXPECT_EQ(header.rfind("t,", 0), 0u);
  EXPECT_NE(header.find(".s_R"), std::string::npos);
  EXPECT_NE(header.find(".s_E"), std::string::npos);
  EXPECT_NE(header.find(".measured"), std::string::npos);
  EXPECT_EQ(first.rfind("0,", 0), 0u);
  EXPECT_NE(slurp(svg).find("<svg"), std::string::npos);
}

TEST(Cli, BadProfileCsvIsLocated) {
  const fs::path prof = scratch("bad_profile.csv");
  std::ofstream(prof) << "t,switch\n0,0\n0.5,abc\n";
  const Result r = efc("play " + q(kSource / "examples/desk_lamp.json") + " --profile csv:" + prof.string() +
                       " --duration 1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(prof.string() + ":3:"), std::string::npos) << r.err;
}

// OSMesa pulls in libLLVM, whose loading cost every command ~20 ms when efc
// linked it; it is opened only when a frame is rendered.
TEST(Cli, OnlyRenderingLoadsOSMesa) {
  // LD_DEBUG=files makes the dynamic loader list every library it opens.
  auto libraries_opened = [](const std::string& args) {
    const fs::path log = scratch("ld-debug.txt");
    const std::string cmd = "LD_DEBUG=files " + std::string(EFC_BINARY_DIR) + "/efc " + args +
                            " >/dev/null 2>" + q(log) + " </dev/null";
    const int status = std::system(cmd.c_str());
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd;
    return slurp(log);
  };
  const std::string check = libraries_opened("check " + q(kSource / "examples/desk_lamp.json"));
  EXPECT_NE(check.find("libmujoco"), std::string::npos) << "LD_DEBUG listed nothing:\n" << check;
  EXPECT_EQ(check.find("libOSMesa"), std::string::npos);
  EXPECT_EQ(check.find("libLLVM"), std::string::npos);

  const fs::path frames = scratch("osmesa-frames");
  const std::string render = libraries_opened("play " + q(kSource / "examples/desk_lamp.json") +
                                              " --profile press:2 --duration 0.1 --render " + q(frames));
  EXPECT_NE(render.find("libOSMesa"), std::string::npos);
  EXPECT_TRUE(fs::exists(frames / "frame_00000.png"));
}

// Text diagnostics on a JSON spec quote the line and put a caret under the
// column, as they do for .efc files; a binary file gets no quoted line.
TEST(Cli, JsonDiagnosticsQuoteTheLineWithACaret) {
  const Result r = efc("check " + q(kSource / "tests/specs/bad/axis_on_fixed.json"));
  ASSERT_EQ(r.exit_code, 1) << r.err;
  std::istringstream lines(r.err);
  std::string first, quoted, caret;
  std::getline(lines, first);
  std::getline(lines, quoted);
  std::getline(lines, caret);
  EXPECT_NE(first.find(":8:59: error[E0211]"), std::string::npos) << r.err;
  EXPECT_EQ(quoted.rfind("  8 | ", 0), 0u) << r.err;
  EXPECT_NE(quoted.find("\"axis\": [0, 0, 1]"), std::string::npos) << r.err;
  // The caret sits under column 59 of the quoted line.
  ASSERT_EQ(caret.rfind("    | ", 0), 0u) << r.err;
  EXPECT_EQ(caret.substr(6), std::string(58, ' ') + "^") << r.err;
  EXPECT_EQ(quoted.substr(6 + 58, 9), "[0, 0, 1]") << r.err;  // the value it is about

  const fs::path binary = scratch("binary.json");
  std::ofstream(binary, std::ios::binary) << std::string("\x01\x02\xff\xfe{\x03\n", 7);
  const Result b = efc("check " + q(binary));
  EXPECT_EQ(b.exit_code, 1) << b.err;
  EXPECT_NE(b.err.find("error[E0004]"), std::string::npos) << b.err;
  EXPECT_EQ(b.err.find(" | "), std::string::npos) << b.err;
}
