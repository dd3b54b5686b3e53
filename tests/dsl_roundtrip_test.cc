// Round trips between the two spellings of a spec (JSON and the .efc DSL):
//   JSON -> DSL -> JSON keeps the document (every example, 300 generated specs);
//   DSL -> JSON -> DSL gives back the same formatted text; print is idempotent;
//   the examples' .efc twins are their JSON documents, already formatted;
//   the same properties for mutated documents the JSON reader accepts but
//   the checks reject (the DSL's contract covers them);
//   comments survive `efc fmt` (print with the file's comments);
//   `efc convert` and `efc fmt` on the command line.
// EFC_SPEC_SEEDS=N runs seeds 0..N-1 instead of 0..299.
// A failing round trip is shrunk to a minimal document the JSON reader still
// accepts, printed with its DSL text and a JSON diff.
#include <gtest/gtest.h>

#include "tests/efc_cli.h"
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compiler/frontend/dsl.h"
#include "compiler/frontend/json_reader.h"
#include "tests/spec_generator.h"
#include "tests/process_temp_dir.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Seeds 0..299; EFC_SPEC_SEEDS=N runs 0..N-1 instead (a longer hunt).
uint64_t seed_count() {
  const char* env = std::getenv("EFC_SPEC_SEEDS");
  return env && *env ? std::strtoull(env, nullptr, 10) : 300;
}
constexpr int kReportedFailures = 3;  // shrunk and printed in full; the rest are counted
const fs::path kSource = EFC_SOURCE_DIR;
const std::string kBaseDir = (kSource / "examples").string();

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void spit(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

std::string messages(const efc::Diagnostics& d) {
  std::ostringstream s;
  for (const auto& x : d.items())
    s << x.file << ":" << x.line << ":" << x.col << ": " << x.code << " " << x.pointer << ": "
      << x.message << "\n";
  return s.str();
}

// The examples' JSON documents, by file name.
std::vector<fs::path> example_files(const std::string& ext) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(kSource / "examples"))
    if (e.path().extension() == ext) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// Everything a round trip runs on: the examples and the generated specs.
struct Case {
  std::string label;
  json doc;
};
std::vector<Case> cases() {
  std::vector<Case> out;
  for (const auto& p : example_files(".json")) out.push_back({p.filename().string(), json::parse(slurp(p))});
  for (uint64_t s = 0, n = seed_count(); s < n; ++s)
    out.push_back({"seed " + std::to_string(s), efc::testing::generate_spec(s)});
  return out;
}

// True when the JSON reader accepts the document (its shape; the DSL's
// contract covers every such document).
bool reader_accepts(const json& doc) {
  efc::Diagnostics d;
  return efc::read_json_text(doc.dump(), "doc.json", kBaseDir, {}, d).has_value();
}

// Documents the JSON reader accepts that are not valid specs, so not what
// the generator makes: numbers at the edges of double (denormals, 1.8e308,
// -0.0, integers beyond 2^53) in spec fields, duplicate part names,
// references to no part or to odd strings ("", "a b", "true", "->"),
// joints changed to another type, a fixed joint with axis and range, parts
// without a joint. The DSL's contract covers them too.
json hostile_spec(uint64_t seed) {
  using efc::testing::spec_gen_detail::Rng;
  json doc = efc::testing::generate_spec(seed);
  Rng rng(seed ^ 0xA5A5A5A5ULL);
  static const std::vector<json> kNumbers = {
      json(5e-324), json(-5e-324), json(2.2250738585072014e-308), json(1.7976931348623157e308),
      json(-1.7976931348623157e308), json(1e-300), json(1e300), json(-0.0), json(0.001),
      json(0.0010000000000000002), json(273.15), json(-273.15), json(0.017453292519943295),
      json(57.29577951308232), json(0.0254), json(999.9999999999999), json(1e-310),
      json(123456789012345678.0), json(1e16), json(-1e-7), json(9007199254740993LL),
      json(-9007199254740993LL), json(std::numeric_limits<int64_t>::max()),
      json(std::numeric_limits<int64_t>::min()), json(std::numeric_limits<uint64_t>::max()),
      json(1000000000000000LL), json(-7)};
  static const std::vector<std::string> kOdd = {"", "a b", "true", "null", "on", "->", "x-y", "part",
                                                "1abc", "\"", "new\nline", "caf\xC3\xA9", "#", ";", "}"};
  // Numbers of spec fields (not inside x- values, not "efc").
  std::vector<json::json_pointer> numbers;
  std::function<void(const json&, const json::json_pointer&)> walk = [&](const json& v,
                                                                         const json::json_pointer& at) {
    if (v.is_object()) {
      for (auto it = v.begin(); it != v.end(); ++it)
        if (it.key().rfind("x-", 0) != 0 && it.key() != "efc") walk(*it, at / it.key());
    } else if (v.is_array()) {
      for (size_t i = 0; i < v.size(); ++i) walk(v[i], at / i);
    } else if (v.is_number()) {
      numbers.push_back(at);
    }
  };
  walk(doc, json::json_pointer());
  for (int64_t k = rng.between(0, 3); k > 0 && !numbers.empty(); --k)
    doc[rng.pick(numbers)] = rng.pick(kNumbers);

  json& parts = doc["parts"];
  std::vector<std::string> names;
  for (const auto& p : parts) names.push_back(p["name"]);
  json* functions = doc.contains("functions") && !doc["functions"].empty() ? &doc["functions"] : nullptr;
  for (int64_t k = rng.between(0, 3); k > 0; --k) {
    json& part = parts[rng.index(parts.size())];
    switch (rng.between(0, 6)) {
      case 0: part["name"] = rng.pick(names); break;  // a duplicate name
      case 1:
      case 2:
        if (functions)
          (*functions)[rng.index(functions->size())][rng.chance(0.5) ? "receptor" : "effector"] =
              rng.chance(0.5) ? rng.pick(names) : rng.pick(kOdd);
        break;
      case 3:
        if (part.contains("joint") && part["joint"]["type"] != "fixed")
          part["joint"]["type"] = rng.pick(std::vector<std::string>{"revolute", "prismatic", "continuous"});
        break;
      case 4:
        if (part.contains("joint") && part["joint"]["type"] == "fixed") {
          part["joint"]["range"] = json::array({-1, 2.5});
          part["joint"]["axis"] = json::array({0, 0, 0});
        }
        break;
      case 5:
        if (part.contains("joint")) part["joint"]["parent"] = rng.pick(kOdd);
        break;
      default: part.erase("joint"); break;
    }
  }
  return doc;
}

std::vector<Case> hostile_cases() {
  std::vector<Case> out;
  for (uint64_t s = 0, n = seed_count(); s < n; ++s) {
    json doc = hostile_spec(s);
    if (reader_accepts(doc)) out.push_back({"hostile seed " + std::to_string(s), std::move(doc)});
  }
  return out;
}

// Numbers equal exactly: nlohmann's == compares an integer with a float
// through double, so 9007199254740993 == 9007199254740992.0; this does not.
bool numbers_exact(const json& a, const json& b, std::string* where, const std::string& ptr = "") {
  if (a.is_number() && b.is_number()) {
    auto wide = [](const json& v) -> long double {
      if (v.is_number_unsigned()) return static_cast<long double>(v.get<uint64_t>());
      if (v.is_number_integer()) return static_cast<long double>(v.get<int64_t>());
      return static_cast<long double>(v.get<double>());
    };
    if (wide(a) != wide(b)) {
      *where = ptr + ": " + a.dump() + " became " + b.dump();
      return false;
    }
    return true;
  }
  if (a.type() != b.type()) return true;  // == reports those
  if (a.is_object()) {
    for (auto it = a.begin(); it != a.end(); ++it) {
      auto jt = b.find(it.key());
      if (jt != b.end() && !numbers_exact(*it, *jt, where, ptr + "/" + it.key())) return false;
    }
  } else if (a.is_array()) {
    for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
      if (!numbers_exact(a[i], b[i], where, ptr + "/" + std::to_string(i))) return false;
  }
  return true;
}

// One parse of DSL text; the document, or the diagnostics in *error.
std::optional<json> parse_dsl(const std::string& text, std::string* error) {
  efc::Diagnostics d;
  std::optional<efc::frontend::PositionedJson> p;
  try {
    p = efc::dsl::parse(text, "roundtrip.efc", 256, d);
  } catch (const std::exception& e) {
    *error = std::string("parse threw: ") + e.what();
    return std::nullopt;
  }
  if (!p || d.has_errors()) {
    *error = "parse failed:\n" + messages(d);
    return std::nullopt;
  }
  return p->value;
}

std::string print_dsl(const json& doc, std::string* error) {
  try {
    return efc::dsl::print(doc);
  } catch (const std::exception& e) {
    *error = std::string("print threw: ") + e.what();
    return {};
  }
}

// Where two texts first differ, for messages.
std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool ea = !std::getline(sa, la), eb = !std::getline(sb, lb);
    if (ea && eb) return "texts differ only in the final newline";
    if (ea || eb || la != lb)
      return "first difference at line " + std::to_string(line) + ":\n  - " + (ea ? "<end>" : la) +
             "\n  + " + (eb ? "<end>" : lb);
  }
}

// ------------------------------------------------------------ the properties
// Each returns "" when it holds, else a kind ("parse", "differs", ...) on the
// first line and the details after it.

std::string json_dsl_json(const json& doc) {
  std::string error;
  const std::string text = print_dsl(doc, &error);
  if (!error.empty()) return "print\n" + error;
  std::optional<json> back = parse_dsl(text, &error);
  if (!back) return "parse\n" + error + "--- DSL:\n" + text;
  if (*back != doc)
    return "differs\n" + json::diff(doc, *back).dump(1) + "\n--- DSL:\n" + text;
  std::string where;
  if (!numbers_exact(doc, *back, &where)) return "number\n" + where + "\n--- DSL:\n" + text;
  return "";
}

std::string dsl_json_dsl(const json& doc) {
  std::string error;
  const std::string text = print_dsl(doc, &error);
  if (!error.empty()) return "print\n" + error;
  std::optional<json> parsed = parse_dsl(text, &error);
  if (!parsed) return "parse\n" + error + "--- DSL:\n" + text;
  std::string json_text;
  try {
    json_text = efc::dsl::print_json(*parsed);
  } catch (const std::exception& e) {
    return std::string("print_json\nthrew ") + e.what();
  }
  json reread = json::parse(json_text, nullptr, false);
  if (reread.is_discarded()) return "print_json\nnot JSON:\n" + json_text;
  const std::string again = print_dsl(reread, &error);
  if (!error.empty()) return "print\n" + error;
  if (again != text)
    return "text\n" + first_difference(text, again) + "\n--- DSL:\n" + text + "--- JSON:\n" + json_text +
           "--- DSL again:\n" + again;
  return "";
}

std::string print_idempotent(const json& doc) {
  std::string error;
  const std::string text = print_dsl(doc, &error);
  if (!error.empty()) return "print\n" + error;
  std::optional<json> parsed = parse_dsl(text, &error);
  if (!parsed) return "parse\n" + error + "--- DSL:\n" + text;
  const std::string again = print_dsl(*parsed, &error);
  if (!error.empty()) return "print\n" + error;
  if (again != text) return "text\n" + first_difference(text, again) + "\n--- DSL:\n" + text;
  return "";
}

std::string print_json_keeps(const json& doc) {
  std::string json_text;
  try {
    json_text = efc::dsl::print_json(doc);
  } catch (const std::exception& e) {
    return std::string("print_json\nthrew ") + e.what();
  }
  json back = json::parse(json_text, nullptr, false);
  if (back.is_discarded()) return "print_json\nnot JSON:\n" + json_text;
  if (back != doc) return "differs\n" + json::diff(doc, back).dump(1) + "\n--- JSON:\n" + json_text;
  std::string where;
  if (!numbers_exact(doc, back, &where)) return "number\n" + where + "\n--- JSON:\n" + json_text;
  return "";
}

// Comments through `efc fmt`: the canonical text with comments added on
// their own lines and at line ends. The comments do not change the
// document; print with the file's comments keeps every one of them, still
// parses to the document, and is formatted (a second fmt changes nothing).
std::string with_comments(const std::string& text, uint64_t seed, std::vector<std::string>* added) {
  efc::testing::spec_gen_detail::Rng rng(seed + 77);
  static const std::vector<std::string> kTails = {"", " plain", " \xC3\xBC \"q\" \\ { ; } ..", " # again",
                                                  " x- 1 .. 2 mm", " }"};
  std::istringstream in(text);
  std::string out;
  int n = 0;
  auto comment = [&] {
    std::string c = " c" + std::to_string(n++) + rng.pick(kTails);
    added->push_back(c);
    return "#" + c;
  };
  for (std::string line; std::getline(in, line);) {
    if (rng.chance(0.25)) out += std::string(static_cast<size_t>(rng.between(0, 6)), ' ') + comment() + "\n";
    out += line;
    if (rng.chance(0.25)) out += std::string(static_cast<size_t>(rng.between(1, 3)), ' ') + comment();
    out += "\n";
  }
  if (rng.chance(0.5)) out += comment() + "\n";
  return out;
}

size_t occurrences(const std::string& hay, const std::string& needle) {
  size_t n = 0;
  for (size_t at = hay.find(needle); at != std::string::npos; at = hay.find(needle, at + 1)) ++n;
  return n;
}

std::string fmt_keeps_comments(const json& doc, uint64_t seed) {
  std::string error;
  const std::string text = print_dsl(doc, &error);
  if (!error.empty()) return "print\n" + error;
  std::vector<std::string> added;
  const std::string commented = with_comments(text, seed, &added);
  efc::Diagnostics d;
  efc::dsl::CommentMap cm;
  auto parsed = efc::dsl::parse_with_comments(commented, "c.efc", 256, d, &cm);
  if (!parsed || d.has_errors()) return "parse\n" + messages(d) + "--- DSL:\n" + commented;
  if (parsed->value != doc)
    return "differs\ncomments changed the document:\n" + json::diff(doc, parsed->value).dump(1) +
           "\n--- DSL:\n" + commented;
  const std::string formatted = efc::dsl::print(parsed->value, &cm);
  for (const auto& c : added) {
    // "#" + text at a line's end, or before a newline.
    size_t found = occurrences(formatted, "#" + c + "\n");
    if (found != 1)
      return "comment\ncomment '#" + c + "' appears " + std::to_string(found) +
             " times after fmt\n--- DSL with comments:\n" + commented + "--- fmt:\n" + formatted;
  }
  std::optional<json> back = parse_dsl(formatted, &error);
  if (!back) return "parse\n" + error + "--- fmt:\n" + formatted;
  if (*back != doc)
    return "differs\n" + json::diff(doc, *back).dump(1) + "\n--- fmt:\n" + formatted;
  efc::Diagnostics d2;
  efc::dsl::CommentMap cm2;
  auto again = efc::dsl::parse_with_comments(formatted, "c.efc", 256, d2, &cm2);
  if (!again) return "parse\n" + messages(d2) + "--- fmt:\n" + formatted;
  const std::string twice = efc::dsl::print(again->value, &cm2);
  if (twice != formatted)
    return "text\nfmt is not idempotent with comments: " + first_difference(formatted, twice) +
           "\n--- DSL with comments:\n" + commented + "--- fmt:\n" + formatted + "--- fmt again:\n" + twice;
  return "";
}

// ------------------------------------------------------------ shrinking
std::string kind_of(const std::string& failure) { return failure.substr(0, failure.find('\n')); }

void pointers(const json& v, const json::json_pointer& at, std::vector<json::json_pointer>& out) {
  out.push_back(at);
  if (v.is_object())
    for (auto it = v.begin(); it != v.end(); ++it) pointers(*it, at / it.key(), out);
  else if (v.is_array())
    for (size_t i = 0; i < v.size(); ++i) pointers(v[i], at / i, out);
}

// Smaller variants of the value at `p` in `doc`: removed, emptied, shortened.
std::vector<json> variants(const json& doc, const json::json_pointer& p) {
  std::vector<json> out;
  if (!p.empty()) {
    json d = doc;
    json& parent = d[p.parent_pointer()];
    if (parent.is_object())
      parent.erase(p.back());
    else
      parent.erase(static_cast<size_t>(std::stoul(p.back())));
    out.push_back(std::move(d));
  }
  const json& v = doc[p];
  auto replaced = [&](json r) {
    json d = doc;
    d[p] = std::move(r);
    out.push_back(std::move(d));
  };
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    if (!s.empty()) {
      replaced(s.substr(0, s.size() / 2));
      replaced(s.substr(s.size() / 2));
      if (s.size() <= 48)
        for (size_t i = 0; i < s.size(); ++i) replaced(s.substr(0, i) + s.substr(i + 1));
    }
  } else if (v.is_number_float()) {
    replaced(0);
    replaced(1);
  }
  return out;
}

// Greedily removes whatever keeps the same kind of failure while the JSON
// reader still accepts the document.
json shrink(json doc, const std::function<std::string(const json&)>& property) {
  const std::string kind = kind_of(property(doc));
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<json::json_pointer> ptrs;
    pointers(doc, json::json_pointer(), ptrs);
    for (const auto& p : ptrs) {
      if (!doc.contains(p)) continue;
      for (json& candidate : variants(doc, p)) {
        if (candidate == doc || !reader_accepts(candidate)) continue;
        const std::string f = property(candidate);
        if (!f.empty() && kind_of(f) == kind) {
          doc = std::move(candidate);
          changed = true;
          break;
        }
      }
    }
  }
  return doc;
}

// Runs a property over every case; the first few failures are shrunk and
// reported with the minimal document.
void check_all(const char* what, const std::function<std::string(const json&)>& property,
               const std::vector<Case>& all_cases = cases()) {
  int failures = 0;
  std::vector<std::string> labels;
  for (const Case& c : all_cases) {
    const std::string f = property(c.doc);
    if (f.empty()) continue;
    ++failures;
    labels.push_back(c.label);
    if (failures > kReportedFailures) continue;
    const json minimal = shrink(c.doc, property);
    ADD_FAILURE() << what << " fails for " << c.label << ": " << f
                  << "\n=== minimal failing document (the JSON reader accepts it):\n"
                  << minimal.dump() << "\n=== its failure: " << property(minimal);
  }
  std::string all;
  for (const auto& l : labels) all += " [" + l + "]";
  EXPECT_EQ(failures, 0) << what << " fails for:" << all;
}

// ------------------------------------------------------------ the CLI
using Result = efc_test::CliResult;

fs::path scratch(const std::string& name) {
  static const efc_test::ProcessTempDir root("efc-dsl-rt-");
  fs::path p = root.path() / name;
  fs::remove_all(p);
  fs::create_directories(p.parent_path());
  return p;
}

Result run_efc(const std::string& args) { return efc_test::run_efc(args); }

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// A folder for converted files, with the examples' meshes (relative mesh
// paths resolve against the spec's folder).
fs::path workdir(const std::string& name) {
  const fs::path dir = scratch(name);
  fs::create_directories(dir);
  fs::copy(kSource / "examples/meshes", dir / "meshes", fs::copy_options::recursive);
  return dir;
}

// Text that is not formatted: the same statements without indentation and
// with blank lines between them.
std::string unformatted(const std::string& text) {
  std::istringstream in(text);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    const size_t start = line.find_first_not_of(' ');
    out += (start == std::string::npos ? std::string() : line.substr(start)) + "\n\n";
  }
  return out;
}

}  // namespace

// ------------------------------------------------------------ the API

TEST(DslRoundTrip, JsonToDslToJsonKeepsTheDocument) {
  check_all("doc -> print -> parse == doc", json_dsl_json);
}

TEST(DslRoundTrip, DslToJsonToDslKeepsTheText) {
  check_all("print(parse(text) -> print_json -> JSON) == text", dsl_json_dsl);
}

TEST(DslRoundTrip, PrintIsIdempotent) {
  check_all("print(parse(print(doc))) == print(doc)", print_idempotent);
}

TEST(DslRoundTrip, PrintJsonKeepsTheDocument) {
  check_all("JSON(print_json(doc)) == doc", print_json_keeps);
}

// Not only valid specs: every document the JSON reader accepts.
TEST(DslRoundTrip, ReaderAcceptedDocumentsRoundTrip) {
  const std::vector<Case> hostile = hostile_cases();
  EXPECT_GT(hostile.size(), seed_count() * 3 / 4) << "most mutated documents should still be readable";
  check_all("hostile: doc -> print -> parse == doc", json_dsl_json, hostile);
  check_all("hostile: print(parse(text) -> print_json -> JSON) == text", dsl_json_dsl, hostile);
  check_all("hostile: print(parse(print(doc))) == print(doc)", print_idempotent, hostile);
  check_all("hostile: JSON(print_json(doc)) == doc", print_json_keeps, hostile);
}

TEST(DslRoundTrip, FmtKeepsEveryComment) {
  uint64_t seed = 0;
  check_all("fmt with comments", [&seed](const json& doc) { return fmt_keeps_comments(doc, seed); });
  // The same documents with other comment placements.
  for (seed = 1; seed < 4; ++seed)
    check_all("fmt with comments (placement seed)", [&seed](const json& doc) { return fmt_keeps_comments(doc, seed); });
}

// Printed DSL is accepted wherever the JSON was: every generated spec's DSL
// parses without a single diagnostic (no warnings either: the printer writes
// units that fit).
TEST(DslRoundTrip, PrintedDslParsesCleanly) {
  for (uint64_t s = 0; s < 50; ++s) {
    const json doc = efc::testing::generate_spec(s);
    const std::string text = efc::dsl::print(doc);
    efc::Diagnostics d;
    auto p = efc::dsl::parse(text, "seed.efc", 256, d);
    EXPECT_TRUE(p.has_value()) << "seed " << s;
    EXPECT_TRUE(d.items().empty()) << "seed " << s << "\n" << messages(d) << text;
  }
}

// examples/X.efc is examples/X.json spelled in the DSL, and already formatted
// (comments included).
TEST(DslRoundTrip, ExampleTwinsMatchTheirJson) {
  const std::vector<fs::path> twins = example_files(".efc");
  if (twins.empty()) GTEST_SKIP() << "no examples/*.efc yet";
  for (const fs::path& efc_file : twins) {
    SCOPED_TRACE(efc_file.filename().string());
    const std::string text = slurp(efc_file);
    efc::Diagnostics d;
    efc::dsl::CommentMap comments;
    auto parsed = efc::dsl::parse_with_comments(text, efc_file.string(), 256, d, &comments);
    ASSERT_TRUE(parsed.has_value()) << messages(d);
    EXPECT_FALSE(d.has_errors()) << messages(d);
    fs::path json_file = efc_file;
    json_file.replace_extension(".json");
    ASSERT_TRUE(fs::exists(json_file)) << "a .efc example needs its .json twin";
    const json want = json::parse(slurp(json_file));
    EXPECT_EQ(parsed->value, want) << json::diff(want, parsed->value).dump(1);
    // Formatted: `efc fmt` (print with the file's comments) leaves it as it is.
    const std::string formatted = efc::dsl::print(parsed->value, &comments);
    EXPECT_EQ(formatted, text) << first_difference(text, formatted);
  }
}

// ------------------------------------------------------------ the CLI

TEST(DslCli, ConvertJsonToEfcToJsonKeepsTheDocument) {
  const fs::path dir = workdir("convert");
  std::vector<std::pair<std::string, json>> docs;
  for (const auto& p : example_files(".json")) docs.push_back({p.stem().string(), json::parse(slurp(p))});
  for (uint64_t s = 0; s < 20; ++s)
    docs.push_back({"seed" + std::to_string(s), efc::testing::generate_spec(s)});
  for (const auto& [stem, doc] : docs) {
    SCOPED_TRACE(stem);
    const fs::path in = dir / (stem + ".json"), mid = dir / (stem + ".efc"),
                   out = dir / (stem + "_back.json");
    spit(in, doc.dump(2));
    Result r = run_efc("convert " + q(in) + " -o " + q(mid));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_TRUE(fs::exists(mid));
    EXPECT_EQ(slurp(mid), efc::dsl::print(doc)) << "convert writes the formatted DSL";
    r = run_efc("convert " + q(mid) + " -o " + q(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json back = json::parse(slurp(out), nullptr, false);
    ASSERT_FALSE(back.is_discarded()) << slurp(out);
    EXPECT_EQ(back, doc) << json::diff(doc, back).dump(1);
    EXPECT_EQ(slurp(out), efc::dsl::print_json(doc)) << "convert writes the canonical JSON";
  }
}

TEST(DslCli, FmtCheckReportsWithoutWriting) {
  const fs::path dir = workdir("fmt-check");
  const std::string formatted = efc::dsl::print(json::parse(slurp(kSource / "examples/microwave.json")));
  const fs::path good = dir / "good.efc", bad = dir / "bad.efc";
  spit(good, formatted);
  spit(bad, unformatted(formatted));
  const std::string bad_before = slurp(bad);
  ASSERT_NE(bad_before, formatted);

  Result r = run_efc("fmt --check " + q(good));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(good), formatted);

  r = run_efc("fmt --check " + q(bad));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(slurp(bad), bad_before) << "--check never writes";

  r = run_efc("fmt --check " + q(good) + " " + q(bad));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(slurp(good), formatted);
  EXPECT_EQ(slurp(bad), bad_before);
}

TEST(DslCli, FmtRewritesInPlace) {
  const fs::path dir = workdir("fmt");
  const fs::path a = dir / "a.efc", b = dir / "b.efc";
  const std::string fa = efc::dsl::print(json::parse(slurp(kSource / "examples/toilet.json")));
  const std::string fb = efc::dsl::print(efc::testing::generate_spec(7));
  spit(a, unformatted(fa));
  spit(b, unformatted(fb));
  Result r = run_efc("fmt " + q(a) + " " + q(b));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(a), fa) << first_difference(fa, slurp(a));
  EXPECT_EQ(slurp(b), fb) << first_difference(fb, slurp(b));
  // Now formatted: --check agrees, and a second fmt changes nothing.
  EXPECT_EQ(run_efc("fmt --check " + q(a) + " " + q(b)).exit_code, 0);
  EXPECT_EQ(run_efc("fmt " + q(a)).exit_code, 0);
  EXPECT_EQ(slurp(a), fa);
  // A .json spec is formatted as canonical JSON, its document unchanged.
  const fs::path c = dir / "c.json";
  const json doc = efc::testing::generate_spec(11);
  spit(c, doc.dump());
  EXPECT_EQ(run_efc("fmt --check " + q(c)).exit_code, 1);
  EXPECT_EQ(slurp(c), doc.dump());
  r = run_efc("fmt " + q(c));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(c), efc::dsl::print_json(doc));
  EXPECT_EQ(json::parse(slurp(c)), doc);
  EXPECT_EQ(run_efc("fmt --check " + q(c)).exit_code, 0);
}

TEST(DslCli, ConvertOfBadInputFailsAndWritesNothing) {
  const fs::path dir = workdir("bad");
  const fs::path bad_json = dir / "bad.json", bad_efc = dir / "bad.efc";
  spit(bad_json, "{\"efc\": 1, \"name\": \"x\", \"parts\": [");
  spit(bad_efc, "efc 1\nobject x {\n  part base { box { size (1, 1, 1) }\n");
  for (const auto& [in, out] : {std::make_pair(bad_json, dir / "out.efc"), std::make_pair(bad_efc, dir / "out.json")}) {
    SCOPED_TRACE(in.filename().string());
    const Result r = run_efc("convert " + q(in) + " -o " + q(out));
    EXPECT_FALSE(r.signaled);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("error["), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
  // A reader error (unknown key) is as bad as a syntax error.
  const fs::path shape = dir / "shape.json";
  spit(shape, R"({"efc": 1, "name": "x", "parts": [{"name": "b", "geometry": {"box": {"size": [1, 1, 1]}}, "colour": 1}]})");
  const Result r = run_efc("convert " + q(shape) + " -o " + q(dir / "shape.efc"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_FALSE(fs::exists(dir / "shape.efc"));
}

TEST(DslCli, UnknownExtensionIsExitTwo) {
  const fs::path dir = workdir("ext");
  const fs::path txt = dir / "spec.txt";
  spit(txt, slurp(kSource / "examples/desk_lamp.json"));
  Result r = run_efc("convert " + q(txt) + " -o " + q(dir / "out.efc"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.efc"));
  r = run_efc("convert " + q(kSource / "examples/desk_lamp.json") + " -o " + q(dir / "out.yaml"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.yaml"));
}
