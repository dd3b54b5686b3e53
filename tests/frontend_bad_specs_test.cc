// Every file in tests/specs/bad/ fails with exactly the errors it expects.
//
// Expectations: a top-level "x-expect": [{"code": ..., "line": ...}] in the
// file when it is valid JSON, else an entry in expectations.json. Files with
// "x-stage": "resolved" fail in check_resolved(); they give every value the
// rule needs explicitly, so it runs here without resolve() (which lives in
// efc_core, not linked by frontend_ tests).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "compiler/frontend/check.h"
#include "compiler/frontend/json_reader.h"

namespace efc {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kBadDir = fs::path(EFC_SOURCE_DIR) / "tests" / "specs" / "bad";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> bad_files() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(kBadDir))
    if (e.path().extension() == ".json" && e.path().filename() != "expectations.json")
      names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

json expectations_for(const std::string& name, std::string* stage) {
  json doc = json::parse(slurp(kBadDir / name), nullptr, /*allow_exceptions=*/false);
  if (!doc.is_discarded() && doc.is_object() && doc.contains("x-expect")) {
    if (doc.contains("x-stage")) *stage = doc["x-stage"].get<std::string>();
    return doc["x-expect"];
  }
  json all = json::parse(slurp(kBadDir / "expectations.json"));
  return all.contains(name) ? all[name] : json();
}

std::multiset<std::pair<std::string, int>> as_set(const json& expect) {
  std::multiset<std::pair<std::string, int>> s;
  for (const auto& e : expect) s.insert({e["code"].get<std::string>(), e["line"].get<int>()});
  return s;
}

class BadSpec : public ::testing::TestWithParam<std::string> {};

TEST_P(BadSpec, FailsWithExpectedCodesAtExpectedLines) {
  const std::string name = GetParam();
  std::string stage;
  json expect = expectations_for(name, &stage);
  ASSERT_TRUE(expect.is_array() && !expect.empty()) << name << " has no expectation";

  Diagnostics diags;
  bool io = false;
  auto obj = read_json_file((kBadDir / name).string(), {}, diags, &io);
  EXPECT_FALSE(io);
  if (obj) {
    check_structure(*obj, diags);
    if (!diags.has_errors() && stage == "resolved") check_resolved(*obj, diags);
  }
  std::multiset<std::pair<std::string, int>> got;
  std::string printed;
  for (const auto& d : diags.items()) {
    printed += format_text(d);
    if (d.severity == Severity::Error) got.insert({d.code, d.line});
    EXPECT_NE(find_code(d.code), nullptr) << d.code << " is not in the catalogue";
  }
  EXPECT_TRUE(diags.has_errors()) << name;
  EXPECT_EQ(got, as_set(expect)) << name << ":\n" << printed;
}

INSTANTIATE_TEST_SUITE_P(All, BadSpec, ::testing::ValuesIn(bad_files()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string n = fs::path(info.param).stem().string();
                           for (auto& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

// Every error code the front-end can emit has at least one bad spec.
TEST(BadSpecs, CoverEveryFrontendErrorCode) {
  std::set<std::string> emitted;
  std::regex code_re("\"(E[0-9]{4})\"");
  for (const auto& e : fs::directory_iterator(fs::path(EFC_SOURCE_DIR) / "compiler" / "frontend")) {
    std::string text = slurp(e.path());
    for (std::sregex_iterator it(text.begin(), text.end(), code_re), end; it != end; ++it)
      emitted.insert((*it)[1]);
  }
  EXPECT_GT(emitted.size(), 40u);
  std::set<std::string> covered;
  for (const auto& name : bad_files()) {
    std::string stage;
    for (const auto& e : expectations_for(name, &stage)) covered.insert(e["code"].get<std::string>());
  }
  // DSL-only codes (syntax, tokens, units) are covered by the golden .efc
  // specs in tests/specs/dsl/, named after their code (dsl_frontend_test.cc).
  for (const auto& e : fs::directory_iterator(fs::path(EFC_SOURCE_DIR) / "tests" / "specs" / "dsl"))
    if (e.path().extension() == ".efc") covered.insert(e.path().filename().string().substr(0, 5));
  emitted.erase("E0001");  // a missing file cannot live in a folder of files (see the reader test)
  for (const auto& c : emitted) {
    EXPECT_TRUE(covered.count(c)) << c << " has no spec in tests/specs/bad/ (or tests/specs/dsl/)";
    EXPECT_NE(find_code(c), nullptr) << c << " is not in the catalogue";
  }
}

}  // namespace
}  // namespace efc
