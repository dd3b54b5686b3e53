// check_structure / check_resolved: every type rule, locations, indices; and
// the code catalogue.
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <set>

#include "compiler/frontend/check.h"
#include "compiler/frontend/json_reader.h"

namespace efc {
namespace {

using nlohmann::json;

// Parts and functions of a small object as JSON; each test edits a copy.
json base_spec() {
  return json::parse(R"({
    "efc": 1, "name": "thing",
    "parts": [
      {"name": "base", "geometry": {"box": {"size": [1, 1, 1]}}},
      {"name": "button", "geometry": {"box": {"size": [0.1, 0.1, 0.1]}},
       "joint": {"type": "prismatic", "parent": "base", "axis": [0, 0, -1], "range": [0, 0.01]}},
      {"name": "lid", "geometry": {"sphere": {"radius": 0.1}},
       "joint": {"type": "revolute", "parent": "base", "axis": [0, 1, 0], "range": [0, 1.5]}},
      {"name": "bulb", "geometry": {"cylinder": {"radius": 0.1, "length": 0.2}},
       "joint": {"type": "fixed", "parent": "base"}}
    ],
    "functions": [
      {"name": "light", "receptor": "button", "effector": "bulb",
       "mapping": {"type": "binary"}, "effect": {"type": "illumination", "range": [0, 400]}}
    ]
  })");
}

Object parse(const json& j) {
  Diagnostics d;
  auto obj = read_json_text(j.dump(2), "t.json", ".", {}, d);
  EXPECT_TRUE(obj) << (d.items().empty() ? "" : format_text(d.items()[0]));
  return obj ? *obj : Object{};
}

struct Checked {
  Object obj;
  Diagnostics diags;
  std::vector<std::string> codes() const {
    std::vector<std::string> c;
    for (const auto& d : diags.items()) c.push_back(d.code);
    return c;
  }
  const Diagnostic& at(size_t i) const { return diags.items().at(i); }
};

Checked structure(const json& j) {
  Checked c{parse(j), {}};
  check_structure(c.obj, c.diags);
  return c;
}

Checked resolved(const json& j) {
  Checked c = structure(j);
  EXPECT_FALSE(c.diags.has_errors());
  check_resolved(c.obj, c.diags);
  return c;
}

// Expects exactly one diagnostic with this code at this pointer.
void expect_one(const Checked& c, const std::string& code, const std::string& pointer) {
  ASSERT_EQ(c.codes(), std::vector<std::string>{code});
  EXPECT_EQ(c.at(0).pointer, pointer);
  EXPECT_GT(c.at(0).line, 0);
  EXPECT_EQ(c.at(0).file, "t.json");
  EXPECT_NE(find_code(code), nullptr) << code << " is not in the catalogue";
}

json& part(json& j, const std::string& name) {
  for (auto& p : j["parts"])
    if (p["name"] == name) return p;
  throw std::runtime_error("no part " + name);
}
json& fn(json& j, size_t i = 0) { return j["functions"][i]; }

TEST(Structure, ValidObjectFillsIndices) {
  Checked c = structure(base_spec());
  EXPECT_TRUE(c.diags.items().empty());
  EXPECT_EQ(c.obj.parts[1].joint->parent_index, 0);
  EXPECT_EQ(c.obj.parts[3].joint->parent_index, 0);
  EXPECT_EQ(c.obj.functions[0].receptor_index, 1);
  EXPECT_EQ(c.obj.functions[0].effector_index, 3);
}

TEST(Structure, Roots) {
  json j = base_spec();
  part(j, "bulb").erase("joint");
  expect_one(structure(j), "E0202", "/parts/3");
  j = base_spec();
  part(j, "base")["joint"] = {{"type", "fixed"}, {"parent", "ghost"}};
  Checked c = structure(j);
  EXPECT_EQ(c.codes(), (std::vector<std::string>{"E0201", "E0204"}));
}

TEST(Structure, Parents) {
  json j = base_spec();
  part(j, "lid")["joint"]["parent"] = "bsae";
  Checked c = structure(j);
  expect_one(c, "E0204", "/parts/2/joint/parent");
  EXPECT_EQ(c.at(0).hint, "did you mean 'base'?");
  EXPECT_EQ(c.obj.parts[2].joint->parent_index, -1);
  j = base_spec();
  part(j, "lid")["joint"]["parent"] = "lid";
  expect_one(structure(j), "E0205", "/parts/2/joint/parent");
}

TEST(Structure, ParentCycle) {
  json j = base_spec();
  part(j, "lid")["joint"]["parent"] = "button";
  part(j, "button")["joint"]["parent"] = "bulb";
  part(j, "bulb")["joint"]["parent"] = "lid";
  Checked c = structure(j);
  expect_one(c, "E0206", "/parts/1/joint/parent");
  EXPECT_NE(c.at(0).message.find("'button' -> 'bulb' -> 'lid' -> 'button'"), std::string::npos)
      << c.at(0).message;
}

TEST(Structure, DuplicateNames) {
  json j = base_spec();
  part(j, "lid")["name"] = "bulb";
  fn(j)["receptor"] = "button";
  Checked c = structure(j);
  ASSERT_EQ(c.codes()[0], "E0207");
  EXPECT_EQ(c.at(0).pointer, "/parts/3/name");
  j = base_spec();
  j["functions"].push_back(fn(j));
  fn(j, 1)["effect"]["type"] = "temperature";
  fn(j, 1)["effect"]["range"] = {20, 100};
  expect_one(structure(j), "E0301", "/functions/1/name");
}

TEST(Structure, JointRanges) {
  json j = base_spec();
  part(j, "lid")["joint"]["range"] = {1.2, 0.3};
  part(j, "lid")["name"] = "handle";
  Checked c = structure(j);
  expect_one(c, "E0203", "/parts/2/joint/range");
  EXPECT_EQ(c.at(0).message, "joint 'handle' range [1.2, 0.3] is not ordered (lo < hi)");
  EXPECT_EQ(c.at(0).hint, "swap the two numbers");
  part(j, "handle")["joint"]["range"] = {0.3, 0.3};
  expect_one(structure(j), "E0203", "/parts/2/joint/range");
  j = base_spec();
  part(j, "lid")["joint"].erase("range");
  expect_one(structure(j), "E0208", "/parts/2/joint/range");
  j = base_spec();
  part(j, "button")["joint"].erase("range");
  expect_one(structure(j), "E0208", "/parts/1/joint/range");
  j = base_spec();
  part(j, "lid")["joint"]["type"] = "continuous";
  expect_one(structure(j), "E0209", "/parts/2/joint/range");
  j = base_spec();
  part(j, "bulb")["joint"]["range"] = {0, 1};
  expect_one(structure(j), "E0209", "/parts/3/joint/range");
}

TEST(Structure, Axes) {
  json j = base_spec();
  part(j, "lid")["joint"]["axis"] = {0, 0, 0};
  expect_one(structure(j), "E0210", "/parts/2/joint/axis");
  j = base_spec();
  part(j, "bulb")["joint"]["axis"] = {0, 0, 1};
  expect_one(structure(j), "E0211", "/parts/3/joint/axis");
  j = base_spec();
  part(j, "lid")["joint"]["axis"] = {0, 2, 0};
  Checked c = structure(j);
  expect_one(c, "W0201", "/parts/2/joint/axis");
  EXPECT_EQ(c.at(0).severity, Severity::Warning);
  EXPECT_FALSE(c.diags.has_errors());
  j = base_spec();
  part(j, "lid")["joint"]["axis"] = {0, 1.0005, 0};  // within 1e-3: fine
  EXPECT_TRUE(structure(j).diags.items().empty());
  j = base_spec();
  part(j, "bulb")["geometry"]["cylinder"]["axis"] = {0, 0, 0};
  expect_one(structure(j), "E0210", "/parts/3/geometry/cylinder/axis");
}

TEST(Structure, OriginOnPrismaticWarns) {
  json j = base_spec();
  part(j, "button")["joint"]["origin"] = {0, 0, 0.1};
  Checked c = structure(j);
  expect_one(c, "W0202", "/parts/1/joint/origin");
  EXPECT_FALSE(c.diags.has_errors());
  part(j, "lid")["joint"]["origin"] = {0, 0, 0.1};  // fine on revolute
  EXPECT_EQ(structure(j).diags.items().size(), 1u);
}

TEST(Structure, PhysicalPartValues) {
  json j = base_spec();
  part(j, "lid")["mass"] = 0;
  expect_one(structure(j), "E0212", "/parts/2/mass");
  j = base_spec();
  part(j, "lid")["geometry"]["sphere"]["radius"] = -1;
  expect_one(structure(j), "E0213", "/parts/2/geometry/sphere/radius");
  j = base_spec();
  part(j, "base")["geometry"]["box"]["size"][1] = 0;
  expect_one(structure(j), "E0213", "/parts/0/geometry/box/size/1");
  j = base_spec();
  part(j, "bulb")["geometry"]["cylinder"]["length"] = 0;
  expect_one(structure(j), "E0213", "/parts/3/geometry/cylinder/length");
  j = base_spec();
  part(j, "lid")["geometry"] = json::parse(R"({"compound": [{"sphere": {"radius": 1}},
                                                            {"box": {"size": [1, -1, 1]}}]})");
  expect_one(structure(j), "E0213", "/parts/2/geometry/compound/1/box/size/1");
  j = base_spec();
  part(j, "lid")["joint"]["damping"] = -1;
  expect_one(structure(j), "E0214", "/parts/2/joint/damping");
  j = base_spec();
  part(j, "lid")["joint"]["friction"] = -1;
  expect_one(structure(j), "E0214", "/parts/2/joint/friction");
  j = base_spec();
  part(j, "lid")["joint"]["spring"] = {{"stiffness", -1}};
  expect_one(structure(j), "E0214", "/parts/2/joint/spring/stiffness");
  part(j, "lid")["joint"]["spring"] = {{"stiffness", 0}};
  expect_one(structure(j), "E0214", "/parts/2/joint/spring/stiffness");
}

TEST(Functions, References) {
  json j = base_spec();
  fn(j)["receptor"] = "buton";
  Checked c = structure(j);
  expect_one(c, "E0302", "/functions/0/receptor");
  EXPECT_EQ(c.at(0).hint, "did you mean 'button'?");
  EXPECT_EQ(c.obj.functions[0].receptor_index, -1);
  j = base_spec();
  fn(j)["effector"] = "ghost";
  expect_one(structure(j), "E0303", "/functions/0/effector");
  j = base_spec();
  fn(j)["effector"] = "button";
  expect_one(structure(j), "E0304", "/functions/0/effector");
  j = base_spec();
  fn(j)["receptor"] = "bulb";
  fn(j)["effector"] = "lid";
  expect_one(structure(j), "E0305", "/functions/0/receptor");
  j = base_spec();
  fn(j)["receptor"] = "base";
  expect_one(structure(j), "E0305", "/functions/0/receptor");
  j = base_spec();
  fn(j)["effect"] = {{"type", "geometry"}};
  expect_one(structure(j), "E0306", "/functions/0/effector");
}

TEST(Functions, TwoWritersOfOneEffect) {
  json j = base_spec();
  j["functions"].push_back(fn(j));
  fn(j, 1)["name"] = "light2";
  fn(j, 1)["receptor"] = "lid";
  expect_one(structure(j), "E0307", "/functions/1/effect/type");
  fn(j, 1)["effect"] = {{"type", "temperature"}};  // another effect type: fine
  EXPECT_TRUE(structure(j).diags.items().empty());
}

TEST(Functions, GraphChainsButNoCycles) {
  json j = base_spec();
  // button -> lid (geometry), lid -> bulb (light): a chain is fine.
  j["functions"].push_back(json::parse(R"({"name": "open", "receptor": "button", "effector": "lid",
      "mapping": {"type": "linear"}, "effect": {"type": "geometry"}})"));
  fn(j)["receptor"] = "lid";
  EXPECT_TRUE(structure(j).diags.items().empty());
  // lid -> button closes a loop.
  j["functions"].push_back(json::parse(R"({"name": "back", "receptor": "lid", "effector": "button",
      "mapping": {"type": "linear"}, "effect": {"type": "geometry"}})"));
  Checked c = structure(j);
  expect_one(c, "E0308", "/functions/2/effector");
  EXPECT_NE(c.at(0).message.find("'open' -> 'back' -> 'open'"), std::string::npos)
      << c.at(0).message;
}

TEST(Functions, EffectValues) {
  json j = base_spec();
  fn(j)["effect"]["range"] = {5, 5};
  expect_one(structure(j), "E0309", "/functions/0/effect/range");
  j = base_spec();
  fn(j)["effect"]["range"] = {400, -1};
  expect_one(structure(j), "E0310", "/functions/0/effect/range/1");
  for (const char* t : {"fluid", "airflow"}) {
    j = base_spec();
    fn(j)["effect"] = {{"type", t}, {"range", {-1, 2}}};
    expect_one(structure(j), "E0310", "/functions/0/effect/range/0");
  }
  j = base_spec();
  fn(j)["effect"] = {{"type", "temperature"}, {"range", {20, -280}}};
  expect_one(structure(j), "E0310", "/functions/0/effect/range/1");
  fn(j)["effect"]["range"] = {20, -273.15};  // absolute zero itself is allowed
  EXPECT_TRUE(structure(j).diags.items().empty());
  fn(j)["effect"]["time_constant"] = 0;
  expect_one(structure(j), "E0311", "/functions/0/effect/time_constant");
  j = base_spec();
  fn(j)["effect"] = json::parse(R"({"type": "fluid", "speed": -1})");
  expect_one(structure(j), "E0311", "/functions/0/effect/speed");
  fn(j)["effect"] = json::parse(R"({"type": "fluid", "droplet_radius": 0})");
  expect_one(structure(j), "E0311", "/functions/0/effect/droplet_radius");
  fn(j)["effect"] = json::parse(R"({"type": "fluid", "emitter": {"direction": [0, 0, 0]}})");
  expect_one(structure(j), "E0322", "/functions/0/effect/emitter/direction");
  fn(j)["effect"] = json::parse(R"({"type": "airflow", "reach": 0})");
  expect_one(structure(j), "E0311", "/functions/0/effect/reach");
  for (double a : {0.0, 1.5708, 20.0, -0.1}) {
    fn(j)["effect"] = {{"type", "airflow"}, {"cone_angle", a}};
    expect_one(structure(j), "E0312", "/functions/0/effect/cone_angle");
  }
  fn(j)["effect"] = {{"type", "airflow"}, {"cone_angle", 0.35}};
  EXPECT_TRUE(structure(j).diags.items().empty());
  j = base_spec();
  fn(j)["effector"] = "lid";
  fn(j)["effect"] = json::parse(R"({"type": "geometry", "stiffness": -1})");
  expect_one(structure(j), "E0313", "/functions/0/effect/stiffness");
  fn(j)["effect"] = json::parse(R"({"type": "geometry", "damping": -1})");
  expect_one(structure(j), "E0313", "/functions/0/effect/damping");
}

TEST(Functions, MappingValues) {
  json j = base_spec();
  fn(j)["mapping"] = {{"type", "cumulative"}};
  expect_one(structure(j), "E0314", "/functions/0/mapping/delta");
  fn(j)["mapping"]["delta"] = 0;
  expect_one(structure(j), "E0315", "/functions/0/mapping/delta");
  fn(j)["mapping"]["delta"] = -50;  // a minus button
  EXPECT_TRUE(structure(j).diags.items().empty());
  fn(j)["mapping"] = {{"type", "linear"}, {"gain", 0}};
  expect_one(structure(j), "E0316", "/functions/0/mapping/gain");
  fn(j)["mapping"]["gain"] = -3;  // negative gain is allowed
  EXPECT_TRUE(structure(j).diags.items().empty());
  fn(j)["mapping"] = {{"type", "step"}, {"hysteresis", -0.1}};
  expect_one(structure(j), "E0319", "/functions/0/mapping/hysteresis");
}

TEST(Functions, ContinuousReceptorNeedsExplicitParameters) {
  json j = base_spec();
  part(j, "lid")["joint"]["type"] = "continuous";
  part(j, "lid")["joint"].erase("range");
  fn(j)["receptor"] = "lid";
  for (const char* t : {"binary", "step", "cumulative"}) {
    fn(j)["mapping"] = {{"type", t}, {"delta", 1}};
    if (std::string(t) != "cumulative") fn(j)["mapping"].erase("delta");
    expect_one(structure(j), "E0317", "/functions/0/mapping/threshold");
    fn(j)["mapping"]["threshold"] = 3.0;
    EXPECT_TRUE(structure(j).diags.items().empty()) << t;
  }
  fn(j)["mapping"] = {{"type", "linear"}};
  expect_one(structure(j), "E0317", "/functions/0/mapping/gain");
  fn(j)["mapping"]["gain"] = 100;
  EXPECT_TRUE(structure(j).diags.items().empty());
}

TEST(Structure, ReportsEveryProblemInOneRun) {
  json j = base_spec();
  part(j, "lid")["joint"]["range"] = {1, 0};   // E0203
  part(j, "bulb")["mass"] = -2;                // E0212
  fn(j)["effect"]["range"] = {400, 400};       // E0309
  Checked c = structure(j);
  std::vector<std::string> got = c.codes();
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, (std::vector<std::string>{"E0203", "E0212", "E0309"}));
  // In file order (the dump puts "functions" before "parts").
  for (size_t i = 1; i < c.diags.items().size(); ++i)
    EXPECT_LE(c.at(i - 1).line, c.at(i).line);
}

// ---------------------------------------------------------------- resolved
TEST(Resolved, ThresholdInsideReceptorRange) {
  json j = base_spec();
  fn(j)["mapping"]["threshold"] = 0.02;
  expect_one(resolved(j), "E0318", "/functions/0/mapping/threshold");
  fn(j)["mapping"]["threshold"] = 0.01;  // the end itself is inside
  EXPECT_TRUE(resolved(j).diags.items().empty());
  fn(j)["mapping"] = {{"type", "step"}, {"threshold", -1}};
  expect_one(resolved(j), "E0318", "/functions/0/mapping/threshold");
  fn(j)["mapping"] = {{"type", "cumulative"}, {"threshold", 1}, {"delta", 10}};
  expect_one(resolved(j), "E0318", "/functions/0/mapping/threshold");
  // Continuous receptor: any finite threshold.
  part(j, "lid")["joint"]["type"] = "continuous";
  part(j, "lid")["joint"].erase("range");
  fn(j)["receptor"] = "lid";
  fn(j)["mapping"]["threshold"] = 100;
  EXPECT_TRUE(resolved(j).diags.items().empty());
}

TEST(Resolved, GeometryRangeInsideJointRange) {
  json j = base_spec();
  fn(j)["effector"] = "lid";
  fn(j)["effect"] = {{"type", "geometry"}, {"range", {1.5, 0}}};  // reversed is fine
  EXPECT_TRUE(resolved(j).diags.items().empty());
  fn(j)["effect"]["range"] = {-0.1, 2};
  Checked c = resolved(j);
  ASSERT_EQ(c.codes(), (std::vector<std::string>{"E0320", "E0320"}));
  EXPECT_EQ(c.at(0).pointer, "/functions/0/effect/range/0");
  EXPECT_EQ(c.at(1).pointer, "/functions/0/effect/range/1");
  part(j, "lid")["joint"]["type"] = "continuous";
  part(j, "lid")["joint"].erase("range");
  EXPECT_TRUE(resolved(j).diags.items().empty());
}

TEST(Resolved, CumulativeInitialInsideEffectRange) {
  json j = base_spec();
  fn(j)["mapping"] = {{"type", "cumulative"}, {"delta", 100}, {"initial", 500}};
  expect_one(resolved(j), "E0321", "/functions/0/mapping/initial");
  fn(j)["effect"]["range"] = {800, 0};  // e_hi below e_lo
  EXPECT_TRUE(resolved(j).diags.items().empty());
}

TEST(Resolved, DefaultedValuesAreLocatedAtTheirMapping) {
  Checked c = structure(base_spec());
  c.obj.functions[0].mapping.threshold = 5;  // as if a faulty default had been filled
  c.obj.functions[0].mapping.defaulted.push_back("threshold");
  check_resolved(c.obj, c.diags);
  ASSERT_EQ(c.codes(), std::vector<std::string>{"E0318"});
  EXPECT_EQ(c.at(0).line, c.obj.functions[0].mapping.loc.line);
}

// ---------------------------------------------------------------- locate / report
TEST(Locate, ExactEnclosingOrUnknown) {
  Object o;
  o.positions[""] = {1, 1};
  o.positions["/parts/0"] = {3, 5};
  o.positions["/parts/0/joint"] = {4, 7};
  SourceLoc l = locate(o, "/parts/0/joint/range");
  EXPECT_EQ(l.pointer, "/parts/0/joint/range");
  EXPECT_EQ(l.line, 4);
  EXPECT_EQ(l.col, 7);
  EXPECT_EQ(locate(o, "/parts/0").line, 3);
  EXPECT_EQ(locate(o, "/functions/2").line, 1);
  Object empty;
  EXPECT_EQ(locate(empty, "/a/b").line, 0);
  o.file = "x.json";
  Diagnostics d;
  report(d, o, "E0203", "/parts/0/joint/range", "msg", "hint");
  report_warning(d, o, "W0201", "/parts/0", "w");
  ASSERT_EQ(d.items().size(), 2u);
  EXPECT_EQ(format_text(d.items()[0]),
            "x.json:4:7: error[E0203]: msg\n  at /parts/0/joint/range\n  hint: hint\n");
  EXPECT_EQ(d.items()[1].severity, Severity::Warning);
  EXPECT_EQ(d.error_count(), 1u);
}

TEST(Structure, HandBuiltIrWithoutPositions) {
  // Another front-end (the DSL) may build the IR directly; checks still work.
  Object o;
  o.parts.resize(2);
  o.parts[0].name = "a";
  o.parts[1].name = "b";
  for (auto& p : o.parts) p.geometry.size = {1, 1, 1};
  o.parts[1].joint.emplace();
  o.parts[1].joint->type = JointType::Revolute;
  o.parts[1].joint->parent = "a";
  Diagnostics d;
  check_structure(o, d);
  ASSERT_EQ(d.items().size(), 1u);
  EXPECT_EQ(d.items()[0].code, "E0208");
  EXPECT_EQ(d.items()[0].line, 0);
  EXPECT_EQ(o.parts[1].joint->parent_index, 0);
}

// ---------------------------------------------------------------- catalogue
TEST(Codes, CatalogueIsWellFormed) {
  std::set<std::string> seen;
  std::regex pattern("[EW][0-9]{4}");
  for (const CodeInfo& c : all_codes()) {
    EXPECT_TRUE(std::regex_match(c.code, pattern)) << c.code;
    EXPECT_TRUE(seen.insert(c.code).second) << "duplicate " << c.code;
    EXPECT_GT(std::string(c.title).size(), 5u) << c.code;
    EXPECT_NE(std::string(c.explanation).find('\n'), std::string::npos) << c.code;
    EXPECT_NE(std::string(c.explanation).find("Fix:"), std::string::npos) << c.code;
    EXPECT_EQ(find_code(c.code), &c);
  }
  for (const char* needed : {"E0001", "E0111", "E0203", "E0900", "W0103", "W0900"})
    EXPECT_TRUE(seen.count(needed)) << needed;
  EXPECT_STREQ(find_code("e0203")->code, "E0203");
  EXPECT_EQ(find_code("E9999"), nullptr);
  EXPECT_EQ(find_code(""), nullptr);
}

}  // namespace
}  // namespace efc
