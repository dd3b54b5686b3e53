// The DSL front-end: golden diagnostics, units, comments, recovery, and that
// .efc twins mean exactly what their .json twins mean through the whole
// compiler. (Round trips over random specs: dsl_roundtrip_test.cc.)
#include <gtest/gtest.h>

#include "tests/efc_cli.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "compiler/core/ir_json.h"
#include "compiler/core/load.h"
#include "compiler/frontend/dsl.h"
#include "compiler/frontend/json_reader.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const fs::path kSource = EFC_SOURCE_DIR;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

using CliRun = efc_test::CliResult;

// Runs efc from the source folder (so paths in messages are relative).
CliRun run_efc(const std::string& args) { return efc_test::run_efc(args, kSource.string()); }

std::optional<json> parse_text(const std::string& text, efc::Diagnostics* diags_out = nullptr) {
  efc::Diagnostics diags;
  auto doc = efc::dsl::parse(text, "t.efc", 256, diags);
  if (diags_out) *diags_out = diags;
  if (!doc) return std::nullopt;
  return doc->value;
}

std::string wrap_part(const std::string& body) {
  return "efc 1\nobject t {\n  part base: base {\n" + body + "\n  }\n}\n";
}

std::vector<std::string> files_with(const fs::path& dir, const std::string& ext) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ext) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

// ---------------------------------------------------------------- golden diagnostics

class DslGolden : public ::testing::TestWithParam<std::string> {};

// tests/specs/dsl/CODE_what.efc: `efc check` prints exactly CODE_what.expected
// (file:line:col, the source line and caret, the pointer and the hint) and
// exits 1. The first diagnostic carries the code the file is named after.
// Regenerate after an intended change: EFC_UPDATE_GOLDEN=1 ctest -R DslGolden
TEST_P(DslGolden, CheckPrintsTheExpectedDiagnostics) {
  const std::string name = GetParam();
  const fs::path efc_file = fs::path("tests/specs/dsl") / name;
  const fs::path expected_file = kSource / "tests/specs/dsl" / (name.substr(0, name.size() - 4) + ".expected");
  const CliRun r = run_efc("check " + efc_file.string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  if (std::getenv("EFC_UPDATE_GOLDEN")) {
    std::ofstream(expected_file, std::ios::binary) << r.err;
    return;
  }
  EXPECT_EQ(r.err, slurp(expected_file)) << "regenerate with EFC_UPDATE_GOLDEN=1 if intended";
  const std::string code = name.substr(0, 5);
  EXPECT_NE(r.err.find("[" + code + "]"), std::string::npos) << r.err;
  // Nothing crashed and nothing was written.
  EXPECT_EQ(r.err.find("terminate called"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Specs, DslGolden,
                         ::testing::ValuesIn(files_with(kSource / "tests/specs/dsl", ".efc")),
                         [](const auto& info) {
                           std::string n = info.param.substr(0, info.param.size() - 4);
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

// tests/specs/bad_dsl/: the DSL twins (efc convert) of the failing JSON specs
// in tests/specs/bad/ that are well-formed enough to convert. Each reports the
// codes its JSON twin's "x-expect" names, located in the .efc file (golden).
class DslBadTwin : public ::testing::TestWithParam<std::string> {};

TEST_P(DslBadTwin, ReportsTheJsonTwinsCodesAtDslLines) {
  const std::string name = GetParam();
  const std::string stem = name.substr(0, name.size() - 4);
  const fs::path dir = kSource / "tests/specs/bad_dsl";
  const CliRun r = run_efc("check tests/specs/bad_dsl/" + name);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  if (std::getenv("EFC_UPDATE_GOLDEN")) {
    std::ofstream(dir / (stem + ".expected"), std::ios::binary) << r.err;
    return;
  }
  EXPECT_EQ(r.err, slurp(dir / (stem + ".expected")));
  const json twin = json::parse(slurp(kSource / "tests/specs/bad" / (stem + ".json")));
  ASSERT_TRUE(twin.contains("x-expect")) << stem;
  for (const auto& e : twin["x-expect"]) {
    const std::string code = e["code"].get<std::string>();
    EXPECT_NE(r.err.find("error[" + code + "]"), std::string::npos) << code << "\n" << r.err;
  }
}

INSTANTIATE_TEST_SUITE_P(Specs, DslBadTwin,
                         ::testing::ValuesIn(files_with(kSource / "tests/specs/bad_dsl", ".efc")),
                         [](const auto& info) {
                           return info.param.substr(0, info.param.size() - 4);
                         });

TEST(DslGolden, EveryDslCodeHasAGoldenFile) {
  const auto files = files_with(kSource / "tests/specs/dsl", ".efc");
  for (const char* code : {"E0002", "E0004", "E0005", "E0006", "E0007", "E0010", "E0011", "E0012",
                           "E0131"}) {
    bool found = false;
    for (const auto& f : files) found = found || f.rfind(code, 0) == 0;
    EXPECT_TRUE(found) << "no tests/specs/dsl/" << code << "_*.efc";
  }
}

// ---------------------------------------------------------------- units

TEST(DslUnits, ConvertToTheSpecsSiValues) {
  auto doc = parse_text(
      "efc 1\nobject t {\n"
      "  part base: base { box { size (10, 20, 5) cm; center (0, 0, 25) mm; rpy (0, 0, 90) deg } }\n"
      "  part knob: receptor {\n"
      "    sphere { radius 0.01 m }\n"
      "    mass 200 kg\n"
      "    joint revolute on base { axis (0, 0, 1); range 0 .. 90 deg; initial 0.5 rad }\n"
      "  }\n"
      "  part plate: effector { sphere { radius 1 cm }; joint fixed on base }\n"
      "  function heat: knob -> plate {\n"
      "    mapping cumulative { threshold 45 deg; delta 10 K; initial 300 K }\n"
      "    effect temperature { range 293.15 .. 473.15 K; time_constant 40 s }\n"
      "  }\n"
      "}\n");
  ASSERT_TRUE(doc);
  const json& d = *doc;
  EXPECT_DOUBLE_EQ(d["parts"][0]["geometry"]["box"]["size"][0].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(d["parts"][0]["geometry"]["box"]["size"][1].get<double>(), 0.2);
  EXPECT_DOUBLE_EQ(d["parts"][0]["geometry"]["box"]["center"][2].get<double>(), 0.025);
  EXPECT_DOUBLE_EQ(d["parts"][0]["geometry"]["box"]["rpy"][2].get<double>(), M_PI / 2);
  EXPECT_DOUBLE_EQ(d["parts"][1]["mass"].get<double>(), 200);
  EXPECT_DOUBLE_EQ(d["parts"][1]["joint"]["range"][1].get<double>(), M_PI / 2);
  EXPECT_DOUBLE_EQ(d["parts"][1]["joint"]["initial"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(d["functions"][0]["mapping"]["threshold"].get<double>(), M_PI / 4);
  // A temperature delta is a difference: 10 K is 10 degrees, not -263.15.
  EXPECT_DOUBLE_EQ(d["functions"][0]["mapping"]["delta"].get<double>(), 10);
  EXPECT_NEAR(d["functions"][0]["mapping"]["initial"].get<double>(), 26.85, 1e-9);
  EXPECT_NEAR(d["functions"][0]["effect"]["range"][0].get<double>(), 20, 1e-9);
  EXPECT_NEAR(d["functions"][0]["effect"]["range"][1].get<double>(), 200, 1e-9);
  EXPECT_DOUBLE_EQ(d["functions"][0]["effect"]["time_constant"].get<double>(), 40);
}

TEST(DslUnits, ABareRangeEndTakesTheOtherEndsUnit) {
  auto doc = parse_text(
      "efc 1\nobject t {\n  part base: base { box { size (1, 1, 1) } }\n"
      "  part b: receptor { box { size (1, 1, 1) }; joint prismatic on base { axis (1, 0, 0); "
      "range 1 .. 4 mm } }\n}\n");
  ASSERT_TRUE(doc);
  EXPECT_DOUBLE_EQ((*doc)["parts"][1]["joint"]["range"][0].get<double>(), 0.001);
  EXPECT_DOUBLE_EQ((*doc)["parts"][1]["joint"]["range"][1].get<double>(), 0.004);
}

TEST(DslUnits, AThresholdFollowsItsReceptorsJointDeclaredLater) {
  // The function comes first; its receptor's joint (prismatic) later.
  const std::string text =
      "efc 1\nobject t {\n"
      "  function f: b -> base { mapping binary { threshold 2 deg }; effect illumination }\n"
      "  part base: base { box { size (1, 1, 1) } }\n"
      "  part b: receptor { box { size (1, 1, 1) }; joint prismatic on base { axis (1, 0, 0); "
      "range 0 .. 4 mm } }\n}\n";
  efc::Diagnostics diags;
  EXPECT_FALSE(parse_text(text, &diags));
  ASSERT_EQ(diags.error_count(), 1u);
  EXPECT_EQ(diags.items()[0].code, "E0131");
  EXPECT_EQ(diags.items()[0].line, 3);
  EXPECT_NE(diags.items()[0].message.find("a length"), std::string::npos);
}

TEST(DslUnits, PrinterPicksTheShortestExactUnit) {
  json doc = {{"efc", 1},
              {"name", "t"},
              {"parts",
               {{{"name", "base"},
                 {"geometry", {{"box", {{"size", {0.1, 0.2, 0.05}}, {"rpy", {0, 0, M_PI / 2}}}}}}},
                {{"name", "b"},
                 {"geometry", {{"sphere", {{"radius", 0.004}}}}},
                 {"joint",
                  {{"type", "revolute"}, {"parent", "base"}, {"axis", {0, 0, 1}},
                   {"range", {-0.5, 0.5}}}}}}}};
  const std::string text = efc::dsl::print(doc);
  EXPECT_NE(text.find("size (10, 20, 5) cm"), std::string::npos) << text;
  EXPECT_NE(text.find("rpy (0, 0, 90) deg"), std::string::npos) << text;
  EXPECT_NE(text.find("radius 4 mm"), std::string::npos) << text;
  EXPECT_NE(text.find("range -0.5 .. 0.5 rad"), std::string::npos) << text;
  EXPECT_NE(text.find("axis (0, 0, 1);"), std::string::npos) << text;
  auto back = parse_text(text);
  ASSERT_TRUE(back);
  EXPECT_EQ(*back, doc);
}

// ---------------------------------------------------------------- comments and fmt

TEST(DslFmt, CommentsSurviveFormatting) {
  const std::string text =
      "efc 1\n# The lamp.\nobject t {\n"
      "  # the base\n"
      "  part base: base {\n"
      "    box { size (1, 1, 1) }   # a cube\n"
      "    mass 2 kg\n"
      "  }\n"
      "}\n# end\n";
  efc::Diagnostics diags;
  efc::dsl::CommentMap comments;
  auto doc = efc::dsl::parse_with_comments(text, "t.efc", 256, diags, &comments);
  ASSERT_TRUE(doc);
  EXPECT_EQ(comments.size(), 4u);
  const std::string out = efc::dsl::print(doc->value, &comments);
  for (const char* c : {"# The lamp.", "  # the base\n  part base", "box { size (1, 1, 1) m }  # a cube",
                        "# end"})
    EXPECT_NE(out.find(c), std::string::npos) << c << "\n" << out;
  // Formatting is idempotent with comments too.
  efc::dsl::CommentMap again;
  auto doc2 = efc::dsl::parse_with_comments(out, "t.efc", 256, diags, &again);
  ASSERT_TRUE(doc2);
  EXPECT_EQ(efc::dsl::print(doc2->value, &again), out);
}

TEST(DslFmt, ExamplesAreFormatted) {
  const CliRun r = run_efc("fmt --check examples/*.efc");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// ---------------------------------------------------------------- robustness

TEST(DslRobustness, EveryPrefixOfAnExampleParsesOrFailsCleanly) {
  const std::string text = slurp(kSource / "examples/desk_lamp.efc");
  ASSERT_FALSE(text.empty());
  size_t failures = 0;
  for (size_t n = 0; n < text.size(); ++n) {
    efc::Diagnostics diags;
    auto doc = efc::dsl::parse(std::string_view(text).substr(0, n), "p.efc", 256, diags);
    if (!doc) {
      ++failures;
      EXPECT_TRUE(diags.has_errors()) << "prefix " << n << " failed without an error";
    }
  }
  EXPECT_GT(failures, text.size() / 2);
}

TEST(DslRobustness, HundredThousandOpenBracesStopAtTheDepthLimit) {
  for (const std::string& opener : {std::string("{ a "), std::string("[")}) {
    std::string text = "efc 1\nobject t {\n  x-deep ";
    if (opener == "{ a ") text = "efc 1\nobject t ";
    for (int i = 0; i < 100000; ++i) text += opener;
    efc::Diagnostics diags;
    EXPECT_FALSE(efc::dsl::parse(text, "deep.efc", 256, diags));
    ASSERT_TRUE(diags.has_errors());
    EXPECT_EQ(diags.items().back().code, "E0005");
  }
}

TEST(DslRobustness, ErrorsAreCappedAndEachLineRecovers) {
  std::string text = "efc 1\nobject t {\n";
  for (int i = 0; i < 1000; ++i) text += "  mass (1 2)\n";
  text += "}\n";
  efc::Diagnostics diags;
  EXPECT_FALSE(efc::dsl::parse(text, "many.efc", 256, diags));
  EXPECT_LE(diags.error_count(), 201u);
  EXPECT_GE(diags.error_count(), 200u);
  // Consecutive errors are on consecutive lines: recovery resumed each time.
  EXPECT_EQ(diags.items()[1].line, diags.items()[0].line + 1);
}

TEST(DslRobustness, NamesCannotSmuggleCode) {
  // A name is an identifier token: quotes, angle brackets and spaces cannot
  // get into one; a quoted name is a string the shape checks reject.
  efc::Diagnostics diags;
  auto obj = efc::read_spec_text(wrap_part("    box { size (1, 1, 1) }\n    name \"a<b>\\\"\""),
                                 "t.efc", ".", {}, diags);
  EXPECT_FALSE(obj);
  EXPECT_TRUE(diags.has_errors());
  diags.clear();
  obj = efc::read_spec_text(
      "efc 1\nobject t {\n  part base: base { mesh \"../../etc/passwd.obj\" }\n}\n", "t.efc", ".",
      {}, diags);
  EXPECT_FALSE(obj);
  bool escape = false;
  for (const auto& d : diags.items()) escape = escape || d.code == "E0112";
  EXPECT_TRUE(escape);
}

// ---------------------------------------------------------------- twins

class DslTwin : public ::testing::TestWithParam<std::string> {};

// The .efc twin of every example resolves to exactly the same IR as its .json.
TEST_P(DslTwin, ResolvesToTheSameIrAsTheJson) {
  const std::string name = GetParam();
  efc::Diagnostics dj, de;
  auto from_json = efc::load_spec((kSource / "examples" / (name + ".json")).string(), {}, dj);
  auto from_dsl = efc::load_spec((kSource / "examples" / (name + ".efc")).string(), {}, de);
  ASSERT_TRUE(from_json) << name;
  ASSERT_TRUE(from_dsl) << name;
  // Everything but where it came from (file, line, column).
  std::function<void(json&)> strip = [&](json& j) {
    if (j.is_object()) {
      j.erase("file");
      j.erase("source");
    }
    if (j.is_structured())
      for (auto& v : j) strip(v);
  };
  json a = efc::ir_to_json(*from_json), b = efc::ir_to_json(*from_dsl);
  strip(a);
  strip(b);
  EXPECT_EQ(a, b) << json::diff(a, b).dump(2);
  EXPECT_EQ(dj.warning_count(), de.warning_count());
}

INSTANTIATE_TEST_SUITE_P(Examples, DslTwin, ::testing::ValuesIn([] {
                           std::vector<std::string> names;
                           for (const auto& f : files_with(kSource / "examples", ".efc"))
                             names.push_back(f.substr(0, f.size() - 4));
                           return names;
                         }()));

TEST(DslTwin, EveryJsonExampleHasATwin) {
  for (const auto& f : files_with(kSource / "examples", ".json")) {
    const std::string stem = f.substr(0, f.size() - 5);
    EXPECT_TRUE(fs::exists(kSource / "examples" / (stem + ".efc"))) << stem;
  }
}

TEST(DslCli, CompileAndPlayAcceptEfcFiles) {
  const fs::path out = fs::temp_directory_path() / ("efc_dsl_cli_" + std::to_string(::getpid()));
  fs::remove_all(out);
  CliRun r = run_efc("compile examples/desk_lamp.efc --target mujoco --target urdf -o " + out.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "mujoco" / "desk_lamp.xml"));
  EXPECT_TRUE(fs::exists(out / "urdf" / "desk_lamp.urdf"));
  const fs::path csv = out / "play.csv";
  r = run_efc("play examples/desk_lamp.efc --profile press:2 --duration 2 --csv " + csv.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(slurp(csv).find("light.s_E"), std::string::npos);
  // A bad .efc compiles to nothing.
  const fs::path none = out / "none";
  r = run_efc("compile tests/specs/dsl/E0010_many_errors.efc --target mujoco -o " + none.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_FALSE(fs::exists(none));
  fs::remove_all(out);
}
