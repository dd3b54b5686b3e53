// The random spec generator (tests/spec_generator.h) makes valid specs, is
// deterministic, and covers every field of spec v1 within seeds 0..299.
#include "tests/spec_generator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "compiler/core/resolve.h"
#include "compiler/frontend/check.h"
#include "compiler/frontend/json_reader.h"

namespace {

using nlohmann::json;

constexpr uint64_t kSeeds = 300;
const std::string kBaseDir = std::string(EFC_SOURCE_DIR) + "/examples";

std::string messages(const efc::Diagnostics& d) {
  std::ostringstream s;
  for (const auto& x : d.items())
    s << x.code << " " << x.pointer << ": " << x.message << "\n";
  return s.str();
}

size_t errors(const efc::Diagnostics& d) {
  size_t n = 0;
  for (const auto& x : d.items()) n += x.severity == efc::Severity::Error;
  return n;
}

// ------------------------------------------------------------ coverage
// Features of a document: JSON pointers with array indices as '*', every `x-`
// key as "x-" (its value not descended into), and joints, mappings and effects
// tagged with their type ("/functions/*/mapping[step]/hysteresis"); plus value
// features ("role=base", "x-value:string-newline", "number:tiny", "chain", ...).
void x_value_features(const json& v, std::set<std::string>& out, int depth) {
  if (depth > 0) out.insert("x-value:nested");
  switch (v.type()) {
    case json::value_t::null: out.insert("x-value:null"); break;
    case json::value_t::boolean: out.insert(v.get<bool>() ? "x-value:true" : "x-value:false"); break;
    case json::value_t::number_integer:
      out.insert(v.get<int64_t>() < 0 ? "x-value:negative-integer" : "x-value:integer");
      break;
    case json::value_t::number_unsigned: out.insert("x-value:integer"); break;
    case json::value_t::number_float: out.insert("x-value:float"); break;
    case json::value_t::string: {
      const std::string s = v.get<std::string>();
      out.insert("x-value:string");
      if (s.find('"') != std::string::npos) out.insert("x-value:string-quote");
      if (s.find('\\') != std::string::npos) out.insert("x-value:string-backslash");
      if (s.find('\n') != std::string::npos) out.insert("x-value:string-newline");
      if (s.find('\x01') != std::string::npos) out.insert("x-value:string-control");
      for (unsigned char c : s)
        if (c >= 0x80) out.insert("x-value:string-unicode");
      if (s.empty()) out.insert("x-value:string-empty");
      break;
    }
    case json::value_t::array:
      out.insert(v.empty() ? "x-value:empty-array" : "x-value:array");
      for (const auto& e : v) x_value_features(e, out, depth + 1);
      break;
    case json::value_t::object:
      out.insert(v.empty() ? "x-value:empty-object" : "x-value:object");
      for (const auto& [k, e] : v.items()) x_value_features(e, out, depth + 1);
      break;
    default: break;
  }
}

void number_features(double x, std::set<std::string>& out) {
  if (x < 0) out.insert("number:negative");
  if (x != 0 && std::fabs(x) <= 1e-6) out.insert("number:tiny");
  if (std::fabs(x) >= 1e4) out.insert("number:large");
  if (x == 0.1) out.insert("number:0.1");
  if (x == 1.0 / 3) out.insert("number:1/3");
  if (x == 3.14159265358979323846 / 2) out.insert("number:pi/2");
  // Needs 16 or 17 significant digits to round-trip.
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", x);
  if (std::strtod(buf, nullptr) != x) out.insert("number:many-digits");
}

void collect(const json& v, const std::string& ptr, std::set<std::string>& out) {
  if (v.is_object()) {
    for (const auto& [k, e] : v.items()) {
      if (k.rfind("x-", 0) == 0) {
        out.insert(ptr + "/x-");
        x_value_features(e, out, 0);
        continue;
      }
      std::string seg = k;
      if ((k == "joint" || k == "mapping" || k == "effect") && e.is_object() && e.contains("type"))
        seg += "[" + e["type"].get<std::string>() + "]";
      out.insert(ptr + "/" + seg);
      collect(e, ptr + "/" + seg, out);
    }
  } else if (v.is_array()) {
    for (const auto& e : v) collect(e, ptr + "/*", out);
  } else if (v.is_number()) {
    number_features(v.get<double>(), out);
  }
}

std::set<std::string> features(const json& doc) {
  std::set<std::string> out;
  collect(doc, "", out);
  for (const auto& p : doc["parts"])
    if (p.contains("role")) out.insert("role=" + p["role"].get<std::string>());
  std::map<std::string, std::string> joint_type;
  for (const auto& p : doc["parts"])
    joint_type[p["name"]] = p.contains("joint") ? p["joint"]["type"].get<std::string>() : "root";
  if (doc.contains("functions")) {
    if (doc["functions"].empty()) out.insert("functions-empty");
    std::set<std::string> receptors, effectors;
    for (const auto& f : doc["functions"]) {
      receptors.insert(f["receptor"]);
      effectors.insert(f["effector"]);
      const std::string rt = joint_type[f["receptor"]], et = joint_type[f["effector"]];
      out.insert("receptor-joint=" + rt);
      out.insert("effect-on-" + et + "=" + f["effect"]["type"].get<std::string>());
      if (rt == "continuous") out.insert("continuous-receptor:" + f["mapping"]["type"].get<std::string>());
      if (f["effect"].contains("range") && f["effect"]["range"][1] < f["effect"]["range"][0])
        out.insert("effect-range-downwards");
    }
    for (const auto& r : receptors)
      if (effectors.count(r)) out.insert("chain");
  }
  return out;
}

std::vector<std::string> expected_features() {
  std::vector<std::string> want = {
      "/efc", "/name", "/description", "/x-", "/parts", "/functions", "functions-empty",
      "/parts/*/name", "/parts/*/role", "/parts/*/geometry", "/parts/*/mass", "/parts/*/rgba",
      "/parts/*/x-", "role=base", "role=receptor", "role=effector", "role=other",
      "/functions/*/name", "/functions/*/receptor", "/functions/*/effector", "/functions/*/x-",
      "chain", "effect-range-downwards",
      "receptor-joint=revolute", "receptor-joint=continuous", "receptor-joint=prismatic",
      "effect-on-continuous=geometry", "effect-on-fixed=illumination", "effect-on-root=temperature",
      "continuous-receptor:binary", "continuous-receptor:step", "continuous-receptor:linear",
      "continuous-receptor:cumulative",
      "number:negative", "number:tiny", "number:large", "number:0.1", "number:1/3", "number:pi/2",
      "number:many-digits",
      "x-value:null", "x-value:true", "x-value:false", "x-value:integer", "x-value:negative-integer",
      "x-value:float", "x-value:string", "x-value:string-quote", "x-value:string-backslash",
      "x-value:string-newline", "x-value:string-control", "x-value:string-unicode",
      "x-value:string-empty", "x-value:array", "x-value:empty-array", "x-value:object",
      "x-value:empty-object", "x-value:nested"};
  // Geometry, at the top and nested in compounds (two levels).
  for (std::string g : {"/parts/*/geometry", "/parts/*/geometry/compound/*",
                        "/parts/*/geometry/compound/*/compound/*"}) {
    for (const char* f : {"/mesh", "/scale", "/x-", "/box", "/box/size", "/box/center", "/box/rpy",
                          "/box/x-", "/cylinder/radius", "/cylinder/length", "/cylinder/center",
                          "/cylinder/axis", "/cylinder/x-", "/sphere/radius", "/sphere/center",
                          "/sphere/x-"})
      want.push_back(g + f);
  }
  want.push_back("/parts/*/geometry/compound");
  want.push_back("/parts/*/geometry/compound/*/compound");
  // Joints.
  for (const char* f : {"/type", "/parent", "/origin", "/x-"})
    want.push_back(std::string("/parts/*/joint[fixed]") + f);
  for (std::string t : {"revolute", "continuous", "prismatic"}) {
    for (const char* f : {"/type", "/parent", "/axis", "/origin", "/initial", "/damping", "/friction",
                          "/spring", "/spring/stiffness", "/spring/rest", "/spring/x-", "/x-"})
      want.push_back("/parts/*/joint[" + t + "]" + f);
    if (t != "continuous") want.push_back("/parts/*/joint[" + t + "]/range");
  }
  // Mappings.
  const std::map<std::string, std::vector<std::string>> mapping_fields = {
      {"binary", {"threshold", "latching"}},
      {"step", {"threshold", "hysteresis"}},
      {"linear", {"gain", "offset"}},
      {"cumulative", {"threshold", "delta", "initial"}}};
  for (const auto& [t, fields] : mapping_fields) {
    const std::string m = "/functions/*/mapping[" + t + "]";
    want.push_back(m + "/type");
    want.push_back(m + "/x-");
    for (const auto& f : fields) want.push_back(m + "/" + f);
  }
  // Effects.
  const std::map<std::string, std::vector<std::string>> effect_fields = {
      {"geometry", {"stiffness", "damping"}},
      {"illumination", {"color", "position"}},
      {"temperature", {"time_constant", "position"}},
      {"fluid", {"emitter", "emitter/position", "emitter/direction", "emitter/x-", "speed",
                 "droplet_radius"}},
      {"airflow", {"outlet", "outlet/position", "outlet/direction", "outlet/x-", "cone_angle", "reach"}}};
  for (const auto& [t, fields] : effect_fields) {
    const std::string e = "/functions/*/effect[" + t + "]";
    for (const char* f : {"/type", "/range", "/x-"}) want.push_back(e + f);
    for (const auto& f : fields) want.push_back(e + "/" + f);
  }
  return want;
}

}  // namespace

TEST(SpecGenerator, IsDeterministic) {
  for (uint64_t seed : {0, 1, 17, 299, 123456789})
    EXPECT_EQ(efc::testing::generate_spec(seed), efc::testing::generate_spec(seed)) << seed;
  EXPECT_NE(efc::testing::generate_spec(1), efc::testing::generate_spec(2));
}

// Every generated spec passes the reader and every type rule (the pipeline
// of load_spec: read, check_structure, resolve, check_resolved).
// EFC_SPEC_SEEDS=N checks seeds 0..N-1 instead of 0..299.
TEST(SpecGenerator, SpecsAreValid) {
  const char* env = std::getenv("EFC_SPEC_SEEDS");
  const uint64_t seeds = env && *env ? std::strtoull(env, nullptr, 10) : kSeeds;
  for (uint64_t seed = 0; seed < seeds; ++seed) {
    const json doc = efc::testing::generate_spec(seed);
    const std::string text = doc.dump(2);
    const std::string file = "seed" + std::to_string(seed) + ".json";
    efc::Diagnostics diags;
    std::optional<efc::Object> obj = efc::read_json_text(text, file, kBaseDir, {}, diags);
    ASSERT_TRUE(obj.has_value()) << file << "\n" << messages(diags) << text;
    efc::check_structure(*obj, diags);
    ASSERT_EQ(errors(diags), 0u) << file << "\n" << messages(diags) << text;
    efc::resolve(*obj, diags);
    ASSERT_EQ(errors(diags), 0u) << file << "\n" << messages(diags) << text;
    efc::check_resolved(*obj, diags);
    ASSERT_EQ(errors(diags), 0u) << file << "\n" << messages(diags) << text;
  }
}

TEST(SpecGenerator, CoversEveryFieldOfSpecV1) {
  std::set<std::string> seen;
  for (uint64_t seed = 0; seed < kSeeds; ++seed) {
    auto f = features(efc::testing::generate_spec(seed));
    seen.insert(f.begin(), f.end());
  }
  std::vector<std::string> missing;
  for (const auto& w : expected_features())
    if (!seen.count(w)) missing.push_back(w);
  std::string list;
  for (const auto& m : missing) list += "  " + m + "\n";
  EXPECT_TRUE(missing.empty()) << "not covered by seeds 0.." << kSeeds - 1 << ":\n" << list;
}
