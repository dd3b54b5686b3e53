// The JSON reader: positions, IR filling, shape errors, malformed input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "compiler/frontend/check.h"
#include "compiler/frontend/json_reader.h"
#include "compiler/frontend/positioned_json.h"

namespace efc {
namespace {

namespace fs = std::filesystem;

struct Result {
  std::optional<Object> obj;
  Diagnostics diags;
};

Result read(const std::string& text, ReadOptions opts = {}, const std::string& base = ".") {
  Result r;
  r.obj = read_json_text(text, "spec.json", base, opts, r.diags);
  return r;
}

// Codes of the errors, in order.
std::vector<std::string> codes(const Diagnostics& d) {
  std::vector<std::string> out;
  for (const auto& x : d.items()) out.push_back(x.code);
  return out;
}

const Diagnostic* find(const Diagnostics& d, const std::string& code) {
  for (const auto& x : d.items())
    if (x.code == code) return &x;
  return nullptr;
}

// A spec with one root; `parts` and `functions` are appended verbatim.
std::string spec(const std::string& extra_parts = "", const std::string& functions = "",
                 const std::string& top = "") {
  std::string s = "{\"efc\": 1, \"name\": \"thing\", " + top +
                  "\"parts\": [{\"name\": \"base\", \"geometry\": {\"box\": {\"size\": [1, 1, 1]}}}" +
                  extra_parts + "]";
  if (!functions.empty()) s += ", \"functions\": [" + functions + "]";
  return s + "}";
}

// Expects exactly one error with this code; returns it.
Diagnostic one_error(const std::string& text, const std::string& code, ReadOptions opts = {}) {
  Result r = read(text, opts);
  EXPECT_FALSE(r.obj.has_value()) << text;
  EXPECT_EQ(codes(r.diags), std::vector<std::string>{code}) << text;
  const Diagnostic* d = find(r.diags, code);
  return d ? *d : Diagnostic{};
}

const char* kLamp = R"({
  "efc": 1,
  "name": "desk_lamp",
  "description": "a lamp",
  "x-origin": {"tool": "hand"},
  "parts": [
    {"name": "base", "role": "base", "geometry": {"box": {"size": [0.15, 0.15, 0.03]}}},
    {"name": "switch", "role": "receptor", "mass": 0.01, "x-part": 1,
     "geometry": {"box": {"size": [0.02, 0.01, 0.01], "center": [0.05, 0, 0.02], "rpy": [0, 0, 0.1]}},
     "joint": {"type": "prismatic", "parent": "base", "axis": [0, 0, -1], "range": [0, 0.004],
               "spring": {"stiffness": 50, "rest": 0}, "damping": 0.1, "x-j": true}},
    {"name": "bulb", "role": "effector", "rgba": [1, 1, 0.5, 1],
     "geometry": {"compound": [{"sphere": {"radius": 0.03, "center": [0, 0, 0.35]}},
                               {"cylinder": {"radius": 0.01, "length": 0.3, "axis": [0, 0, 1]}}]},
     "joint": {"type": "fixed", "parent": "base"}}
  ],
  "functions": [
    {"name": "light", "receptor": "switch", "effector": "bulb",
     "mapping": {"type": "binary", "latching": true, "x-m": "kept"},
     "effect": {"type": "illumination", "range": [0, 450], "color": [1.0, 0.9, 0.8]}},
    {"name": "spray", "receptor": "switch", "effector": "bulb",
     "mapping": {"type": "cumulative", "delta": -1.5},
     "effect": {"type": "fluid", "emitter": {"position": [0, 0, 0.1], "direction": [0, 0, -1], "x-e": 2},
                "speed": 1.0}}
  ]
})";

TEST(Reader, FillsTheIr) {
  Result r = read(kLamp);
  ASSERT_TRUE(r.obj) << codes(r.diags).size();
  EXPECT_EQ(r.diags.items().size(), 0u);
  const Object& o = *r.obj;
  EXPECT_EQ(o.name, "desk_lamp");
  EXPECT_EQ(o.description, "a lamp");
  EXPECT_EQ(o.file, "spec.json");
  ASSERT_EQ(o.parts.size(), 3u);
  EXPECT_EQ(o.parts[0].role, PartRole::Base);
  EXPECT_FALSE(o.parts[0].joint);
  EXPECT_FALSE(o.parts[0].mass);  // defaults are resolve()'s job
  const Part& sw = o.parts[1];
  EXPECT_EQ(sw.geometry.kind, GeomKind::Box);
  EXPECT_EQ(sw.geometry.center, (Vec3{0.05, 0, 0.02}));
  EXPECT_EQ(sw.geometry.rpy, (Vec3{0, 0, 0.1}));
  EXPECT_DOUBLE_EQ(*sw.mass, 0.01);
  ASSERT_TRUE(sw.joint);
  EXPECT_EQ(sw.joint->type, JointType::Prismatic);
  EXPECT_EQ(sw.joint->parent, "base");
  EXPECT_TRUE(sw.joint->has_axis);
  EXPECT_EQ(sw.joint->axis, (Vec3{0, 0, -1}));
  EXPECT_FALSE(sw.joint->has_origin);
  EXPECT_TRUE(sw.joint->has_range);
  EXPECT_DOUBLE_EQ(sw.joint->hi, 0.004);
  EXPECT_FALSE(sw.joint->initial);
  EXPECT_DOUBLE_EQ(sw.joint->damping, 0.1);
  ASSERT_TRUE(sw.joint->spring);
  EXPECT_DOUBLE_EQ(sw.joint->spring->stiffness, 50);
  const Part& bulb = o.parts[2];
  ASSERT_TRUE(bulb.rgba);
  EXPECT_DOUBLE_EQ((*bulb.rgba)[2], 0.5);
  ASSERT_EQ(bulb.geometry.kind, GeomKind::Compound);
  ASSERT_EQ(bulb.geometry.children.size(), 2u);
  EXPECT_EQ(bulb.geometry.children[0].kind, GeomKind::Sphere);
  EXPECT_DOUBLE_EQ(bulb.geometry.children[1].length, 0.3);
  EXPECT_EQ(bulb.geometry.children[1].loc.pointer, "/parts/2/geometry/compound/1");
  ASSERT_EQ(o.functions.size(), 2u);
  const Function& f = o.functions[0];
  EXPECT_EQ(f.mapping.type, MappingType::Binary);
  EXPECT_EQ(f.mapping.latching, true);
  EXPECT_FALSE(f.mapping.threshold);
  EXPECT_TRUE(f.effect.has_range);
  EXPECT_DOUBLE_EQ(f.effect.hi, 450);
  EXPECT_EQ(f.effect.color, (Vec3{1.0, 0.9, 0.8}));
  EXPECT_EQ(f.receptor_index, -1);  // check() fills it
  const Function& g = o.functions[1];
  EXPECT_EQ(g.mapping.delta, -1.5);
  EXPECT_EQ(g.effect.type, EffectType::Fluid);
  EXPECT_FALSE(g.effect.has_range);
  EXPECT_EQ(g.effect.position, (Vec3{0, 0, 0.1}));
  EXPECT_EQ(g.effect.direction, (Vec3{0, 0, -1}));
  EXPECT_EQ(g.effect.speed, 1.0);
}

TEST(Reader, KeepsExtensionKeys) {
  Result r = read(kLamp);
  ASSERT_TRUE(r.obj);
  const Object& o = *r.obj;
  EXPECT_EQ(o.extensions.at("x-origin"), nlohmann::json({{"tool", "hand"}}));
  EXPECT_EQ(o.parts[1].extensions.at("x-part"), 1);
  EXPECT_EQ(o.parts[1].joint->extensions.at("x-j"), true);
  EXPECT_EQ(o.functions[0].mapping.extensions.at("x-m"), "kept");
  EXPECT_EQ(o.functions[1].effect.point_extensions.at("x-e"), 2);
}

TEST(Reader, RecordsExactPositions) {
  Result r = read(kLamp);
  ASSERT_TRUE(r.obj);
  const Object& o = *r.obj;
  // line 10: `     "joint": {"type": "prismatic", "parent": "base", "axis": [0, 0, -1], "range": [0, 0.004],`
  EXPECT_EQ(o.positions.at("/parts/1/joint/range"), std::make_pair(10, 84));
  EXPECT_EQ(o.positions.at("/parts/1/joint/range/1"), std::make_pair(10, 88));
  EXPECT_EQ(o.positions.at("/parts/1/joint"), std::make_pair(10, 15));
  EXPECT_EQ(o.positions.at(frontend::key_position("/parts/1/joint")), std::make_pair(10, 6));
  EXPECT_EQ(o.positions.at(""), std::make_pair(1, 1));
  EXPECT_EQ(o.positions.at("/efc"), std::make_pair(2, 10));
  EXPECT_EQ(o.positions.at("/x-origin/tool"), std::make_pair(5, 24));
  // IR nodes carry their locations.
  EXPECT_EQ(o.parts[1].joint->loc.pointer, "/parts/1/joint");
  EXPECT_EQ(o.parts[1].joint->loc.line, 10);
  EXPECT_EQ(o.parts[1].joint->loc.col, 15);
  EXPECT_EQ(o.parts[1].loc.line, 8);
  EXPECT_EQ(o.parts[1].loc.col, 5);
  EXPECT_EQ(o.functions[1].mapping.loc.line, 22);
  EXPECT_EQ(o.functions[1].effect.loc.pointer, "/functions/1/effect");
  EXPECT_EQ(o.parts[2].joint->spring ? 1 : 0, 0);
  EXPECT_EQ(o.parts[1].joint->spring->loc.line, 11);
}

TEST(Reader, ColumnsCountCharactersAndSkipBom) {
  // "é" is two bytes but one column; the BOM is invisible.
  Result r = read("\xEF\xBB\xBF{\"description\": \"\xC3\xA9\", \"efc\": 1}");
  EXPECT_EQ(find(r.diags, "E0102")->line, 1);
  Diagnostics d;
  auto p = frontend::parse_positioned("\xEF\xBB\xBF{\"d\": \"\xC3\xA9\", \"e\": 1}", "f", 256, d);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->positions.at(""), std::make_pair(1, 1));
  EXPECT_EQ(p->positions.at("/e"), std::make_pair(1, 17));
}

TEST(Reader, CrLfLineEndings) {
  Diagnostics d;
  auto p = frontend::parse_positioned("{\r\n  \"a\": 1,\r\n  \"b\": [true]\r\n}", "f", 256, d);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->positions.at("/b/0"), std::make_pair(3, 9));
  EXPECT_EQ(p->positions.at("/b"), std::make_pair(3, 8));
}

TEST(Reader, PointerEscaping) {
  Diagnostics d;
  auto p = frontend::parse_positioned(R"({"a/b": {"c~d": 1}})", "f", 256, d);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->positions.at("/a~1b/c~0d"), std::make_pair(1, 17));
}

// ---------------------------------------------------------------- malformed input
TEST(Malformed, Empty) {
  EXPECT_EQ(one_error("", "E0002").line, 1);
  one_error("  \n\t\n", "E0002");
  one_error("\xEF\xBB\xBF", "E0002");
}

TEST(Malformed, Truncated) {
  Diagnostic d = one_error("{\n  \"efc\": 1,\n  \"parts\": [\n", "E0003");
  EXPECT_EQ(d.line, 3);  // just after the last thing written
  EXPECT_EQ(d.col, 13);
  one_error("{\"efc\": 1, \"name\": \"ab", "E0003");
  one_error("{", "E0003");
}

TEST(Malformed, TrailingComma) {
  Diagnostic d = one_error("{\"efc\": 1,\n \"parts\": [1, 2,]}", "E0003");
  EXPECT_EQ(d.line, 2);
  EXPECT_EQ(d.col, 17);  // the ']'
  EXPECT_NE(d.hint.find("trailing comma"), std::string::npos);
  one_error("{\"efc\": 1,}", "E0003");
}

TEST(Malformed, OtherSyntax) {
  EXPECT_EQ(one_error("{\"efc\": 1, \"a\": tru}", "E0003").col, 17);  // the start of the word
  one_error("{\"efc\": 1} {}", "E0003");                                // trailing content
  one_error("// comment\n{}", "E0003");
  one_error("{'efc': 1}", "E0003");
  one_error(std::string("{\"efc\": 1, \"a\": \"x\0y\"}", 21), "E0003");  // NUL in a string
  one_error(std::string("{\"efc\": 1\0}", 11), "E0003");
}

TEST(Malformed, BinaryAndInvalidUtf8) {
  Diagnostic d = one_error("{\n  \"name\": \"a\xFF\"}", "E0004");
  EXPECT_EQ(d.line, 2);
  EXPECT_EQ(d.col, 13);
  one_error("\x89PNG\r\n\x1a\n\x00\x00", "E0004");
  one_error("{\"a\": \"\xC0\xAF\"}", "E0004");          // overlong '/'
  one_error("{\"a\": \"\xED\xA0\x80\"}", "E0004");      // surrogate
  one_error("{\"a\": \"\xE2\x82\"}", "E0004");          // cut sequence
  std::string all;
  for (int i = 0; i < 256; ++i) all += static_cast<char>(i);
  one_error(all, "E0004");
}

TEST(Malformed, DeepNestingIsAnErrorNotACrash) {
  for (const char* open : {"[", "{\"a\":"}) {
    std::string deep;
    for (int i = 0; i < 100000; ++i) deep += open;
    Diagnostic d = one_error(deep, "E0005");
    EXPECT_EQ(d.line, 1);
  }
  std::string closed = std::string(100000, '[') + std::string(100000, ']');
  one_error(closed, "E0005");
  // The limit is an option; under it nesting is fine (the shape error is E0101).
  ReadOptions opts;
  opts.max_depth = 300;
  std::string ok = "{\"efc\": 1, \"x-d\": " + std::string(200, '[') + std::string(200, ']') + "}";
  Result r = read(ok, opts);
  EXPECT_EQ(find(r.diags, "E0005"), nullptr);
}

TEST(Malformed, NumberOverflow) {
  Diagnostic d = one_error("{\"efc\": 1,\n \"name\": 1e999}", "E0006");
  EXPECT_EQ(d.line, 2);
  EXPECT_EQ(d.col, 10);
  EXPECT_EQ(d.pointer, "/name");
  one_error("{\"efc\": -1e999}", "E0006");
  one_error("{\"efc\": " + std::string(400, '9') + "}", "E0006");
}

TEST(Malformed, DuplicateKey) {
  Result r = read(spec(", {\"name\": \"lid\", \"mass\": 1,\n \"mass\": 2, "
                       "\"geometry\": {\"box\": {\"size\": [1, 1, 1]}}, "
                       "\"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"));
  EXPECT_FALSE(r.obj);
  ASSERT_EQ(codes(r.diags), std::vector<std::string>{"E0007"});
  EXPECT_EQ(r.diags.items()[0].line, 2);
  EXPECT_EQ(r.diags.items()[0].col, 2);
  EXPECT_EQ(r.diags.items()[0].pointer, "/parts/1/mass");
}

TEST(Malformed, NotAnObject) {
  one_error("[1, 2]", "E0101");
  one_error("42", "E0101");
  one_error("null", "E0101");
}

// ---------------------------------------------------------------- shape
TEST(Shape, ValidMinimalSpec) {
  Result r = read(spec());
  EXPECT_TRUE(r.obj);
  EXPECT_TRUE(r.diags.items().empty());
}

TEST(Shape, Version) {
  Diagnostic d = one_error("{\"efc\": 2, \"name\": \"a\", \"parts\": [{\"name\": \"b\", "
                           "\"geometry\": {\"sphere\": {\"radius\": 1}}}]}",
                           "E0104");
  EXPECT_EQ(d.pointer, "/efc");
  one_error("{\"efc\": \"1\", \"name\": \"a\", \"parts\": [{\"name\": \"b\", "
            "\"geometry\": {\"sphere\": {\"radius\": 1}}}]}",
            "E0104");
  one_error("{\"efc\": 1.5, \"name\": \"a\", \"parts\": [{\"name\": \"b\", "
            "\"geometry\": {\"sphere\": {\"radius\": 1}}}]}",
            "E0104");
}

TEST(Shape, MissingRequired) {
  Result r = read("{\"efc\": 1}");
  EXPECT_EQ(codes(r.diags), (std::vector<std::string>{"E0102", "E0102"}));
  one_error(spec(", {\"name\": \"x\", \"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"),
            "E0102");
  Diagnostic d = one_error(spec(", {\"name\": \"x\", \"geometry\": {\"box\": {\"size\": [1, 1, 1]}}, "
                                "\"joint\": {\"type\": \"fixed\"}}"),
                           "E0102");
  EXPECT_EQ(d.pointer, "/parts/1/joint/parent");
  one_error(spec("", "{\"name\": \"f\", \"receptor\": \"a\", \"effector\": \"b\", "
                     "\"mapping\": {\"type\": \"binary\"}}"),
            "E0102");
  one_error(spec("", "{\"name\": \"f\", \"receptor\": \"a\", \"effector\": \"b\", "
                     "\"mapping\": {}, \"effect\": {\"type\": \"fluid\"}}"),
            "E0102");
  one_error("{\"efc\": 1, \"name\": \"a\", \"parts\": [{\"name\": \"b\", "
            "\"geometry\": {\"cylinder\": {\"radius\": 1}}}]}",
            "E0102");
  one_error(spec(", {\"name\": \"x\", \"geometry\": {\"box\": {\"size\": [1, 1, 1]}}, "
                 "\"joint\": {\"type\": \"prismatic\", \"parent\": \"base\", \"range\": [0, 1], "
                 "\"spring\": {\"rest\": 0}}}"),
            "E0102");
}

TEST(Shape, WrongTypes) {
  one_error(spec("", "", "\"description\": 3, "), "E0101");
  one_error("{\"efc\": 1, \"name\": 7, \"parts\": [{\"name\": \"b\", "
            "\"geometry\": {\"sphere\": {\"radius\": 1}}}]}",
            "E0101");
  one_error("{\"efc\": 1, \"name\": \"a\", \"parts\": {}}", "E0101");
  one_error(spec("", "", "\"functions\": {}, "), "E0101");
  one_error(spec(", 5"), "E0101");
  Diagnostic d = one_error(spec(", {\"name\": \"x\", \"mass\": \"2\", \"geometry\": {\"box\": "
                                "{\"size\": [1, 1, 1]}}, \"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"),
                           "E0101");
  EXPECT_EQ(d.pointer, "/parts/1/mass");
  one_error(spec(", {\"name\": \"x\", \"mass\": true, \"geometry\": {\"box\": {\"size\": [1, 1, 1]}}, "
                 "\"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"),
            "E0101");
  one_error(spec(", {\"name\": \"x\", \"geometry\": {\"box\": {\"size\": [1, \"1\", 1]}}, "
                 "\"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"),
            "E0101");
  one_error(spec(", {\"name\": \"x\", \"geometry\": {\"mesh\": 3}, "
                 "\"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"),
            "E0101");
  one_error(spec(", {\"name\": \"x\", \"geometry\": [], "
                 "\"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"),
            "E0101");
  one_error(spec(", {\"name\": \"x\", \"geometry\": {\"box\": {\"size\": [1, 1, 1]}}, "
                 "\"joint\": {\"type\": \"fixed\", \"parent\": null}}"),
            "E0101");
  one_error(spec(", {\"name\": \"x\", \"geometry\": {\"box\": {\"size\": [1, 1, 1]}}, \"joint\": 1}"),
            "E0101");
  one_error(spec("", "{\"name\": \"f\", \"receptor\": \"a\", \"effector\": \"b\", "
                     "\"mapping\": {\"type\": \"binary\", \"latching\": 1}, \"effect\": {\"type\": \"fluid\"}}"),
            "E0101");
  one_error(spec("", "{\"name\": \"f\", \"receptor\": \"a\", \"effector\": \"b\", "
                     "\"mapping\": {\"type\": \"binary\"}, \"effect\": {\"type\": \"fluid\", \"emitter\": [0, 0, 1]}}"),
            "E0101");
}

TEST(Shape, UnknownKeysWithSuggestions) {
  Diagnostic d = one_error(spec("", "", "\"nmae\": \"x\", "), "E0103");
  EXPECT_EQ(d.hint, "did you mean 'name'?");
  EXPECT_EQ(d.pointer, "/nmae");
  // Keys of another mapping / effect type are unknown here.
  one_error(spec("", "{\"name\": \"f\", \"receptor\": \"a\", \"effector\": \"b\", "
                     "\"mapping\": {\"type\": \"binary\", \"delta\": 1}, \"effect\": {\"type\": \"fluid\"}}"),
            "E0103");
  one_error(spec("", "{\"name\": \"f\", \"receptor\": \"a\", \"effector\": \"b\", "
                     "\"mapping\": {\"type\": \"linear\"}, \"effect\": {\"type\": \"illumination\", "
                     "\"emitter\": {}}}"),
            "E0103");
  one_error(spec("", "{\"name\": \"f\", \"receptor\": \"a\", \"effector\": \"b\", "
                     "\"mapping\": {\"type\": \"linear\"}, \"effect\": {\"type\": \"airflow\", "
                     "\"outlet\": {\"pos\": [0, 0, 0]}}}"),
            "E0103");
  one_error(spec(", {\"name\": \"x\", \"geometry\": {\"sphere\": {\"radius\": 1}, \"scale\": [1, 1, 1]}, "
                 "\"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"),
            "E0103");
  one_error(spec(", {\"name\": \"x\", \"geometry\": {\"sphere\": {\"radius\": 1, \"size\": 1}}, "
                 "\"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"),
            "E0103");
  // A fixed joint takes no motion parameters.
  for (const char* k : {"\"spring\": {\"stiffness\": 1}", "\"damping\": 0", "\"initial\": 0",
                        "\"friction\": 0"}) {
    Diagnostic d = one_error(spec(std::string(", {\"name\": \"x\", \"geometry\": {\"sphere\": "
                                              "{\"radius\": 1}}, \"joint\": {\"type\": \"fixed\", "
                                              "\"parent\": \"base\", ") + k + "}}"),
                             "E0103");
    EXPECT_NE(d.message.find("fixed joint"), std::string::npos);
  }
  // x- keys are fine anywhere, including inside primitives and emitters.
  Result r = read(spec(", {\"name\": \"x\", \"geometry\": {\"sphere\": {\"radius\": 1, \"x-a\": 1}, "
                       "\"x-b\": 2}, \"joint\": {\"type\": \"revolute\", \"parent\": \"base\", "
                       "\"range\": [0, 1], \"spring\": {\"stiffness\": 1, \"x-c\": 3}}}"));
  EXPECT_TRUE(r.obj);
  EXPECT_EQ(r.obj->parts[1].geometry.extensions.at("x-b"), 2);
}

TEST(Shape, Names) {
  for (const char* bad : {"a\\\"b", "<lid>", "a b", "1abc", "", "a-b", "caf\xC3\xA9"}) {
    Diagnostic d = one_error(spec(std::string(", {\"name\": \"") + bad +
                                  "\", \"geometry\": {\"sphere\": {\"radius\": 1}}, "
                                  "\"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"),
                             "E0105");
    EXPECT_EQ(d.pointer, "/parts/1/name");
  }
  one_error("{\"efc\": 1, \"name\": \"the thing\", \"parts\": [{\"name\": \"b\", "
            "\"geometry\": {\"sphere\": {\"radius\": 1}}}]}",
            "E0105");
  Diagnostic d = one_error(spec(", {\"name\": \"efc_lid\", \"geometry\": {\"sphere\": {\"radius\": 1}}, "
                                "\"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"),
                           "E0106");
  EXPECT_NE(d.hint.find("efc_"), std::string::npos);
  one_error(spec("", "{\"name\": \"efc_f\", \"receptor\": \"a\", \"effector\": \"b\", "
                     "\"mapping\": {\"type\": \"binary\"}, \"effect\": {\"type\": \"fluid\"}}"),
            "E0106");
}

TEST(Shape, IsValidName) {
  EXPECT_TRUE(is_valid_name("a"));
  EXPECT_TRUE(is_valid_name("_x9"));
  EXPECT_TRUE(is_valid_name(std::string(64, 'a')));
  EXPECT_FALSE(is_valid_name(std::string(65, 'a')));
  EXPECT_FALSE(is_valid_name(""));
  EXPECT_FALSE(is_valid_name("9a"));
  EXPECT_FALSE(is_valid_name("a\"b"));
  EXPECT_FALSE(is_valid_name("a<b"));
  EXPECT_FALSE(is_valid_name("a.b"));
  EXPECT_FALSE(is_valid_name(std::string_view("a\0b", 3)));
}

TEST(Shape, EnumValues) {
  Diagnostic d = one_error(spec(", {\"name\": \"x\", \"role\": \"efector\", \"geometry\": {\"sphere\": "
                                "{\"radius\": 1}}, \"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"),
                           "E0107");
  EXPECT_EQ(d.hint, "did you mean 'effector'?");
  d = one_error(spec(", {\"name\": \"x\", \"geometry\": {\"sphere\": {\"radius\": 1}}, "
                     "\"joint\": {\"type\": \"hinge\", \"parent\": \"base\"}}"),
                "E0107");
  EXPECT_NE(d.hint.find("revolute"), std::string::npos);
  one_error(spec("", "{\"name\": \"f\", \"receptor\": \"a\", \"effector\": \"b\", "
                     "\"mapping\": {\"type\": \"toggle\", \"gain\": 1}, \"effect\": {\"type\": \"fluid\"}}"),
            "E0107");  // and no follow-up unknown-key error for "gain"
  one_error(spec("", "{\"name\": \"f\", \"receptor\": \"a\", \"effector\": \"b\", "
                     "\"mapping\": {\"type\": \"binary\"}, \"effect\": {\"type\": \"sound\", \"range\": [0, 1]}}"),
            "E0107");
}

TEST(Shape, GeometryKinds) {
  one_error("{\"efc\": 1, \"name\": \"a\", \"parts\": [{\"name\": \"b\", \"geometry\": {}}]}", "E0108");
  one_error("{\"efc\": 1, \"name\": \"a\", \"parts\": [{\"name\": \"b\", \"geometry\": "
            "{\"sphere\": {\"radius\": 1}, \"box\": {\"size\": [1, 1, 1]}}}]}",
            "E0108");
  one_error("{\"efc\": 1, \"name\": \"a\", \"parts\": [{\"name\": \"b\", \"geometry\": "
            "{\"compound\": []}}]}",
            "E0116");
  one_error("{\"efc\": 1, \"name\": \"a\", \"parts\": []}", "E0116");
  // Nested compound errors point inside.
  Diagnostic d = one_error("{\"efc\": 1, \"name\": \"a\", \"parts\": [{\"name\": \"b\", \"geometry\": "
                           "{\"compound\": [{\"sphere\": {\"radius\": 1}}, {\"compound\": [{}]}]}}]}",
                           "E0108");
  EXPECT_EQ(d.pointer, "/parts/0/geometry/compound/1/compound/0");
}

TEST(Shape, ArrayLengthsAndColours) {
  one_error(spec(", {\"name\": \"x\", \"geometry\": {\"sphere\": {\"radius\": 1}}, "
                 "\"joint\": {\"type\": \"revolute\", \"parent\": \"base\", \"axis\": [0, 1], \"range\": [0, 1]}}"),
            "E0109");
  one_error(spec(", {\"name\": \"x\", \"geometry\": {\"sphere\": {\"radius\": 1}}, "
                 "\"joint\": {\"type\": \"revolute\", \"parent\": \"base\", \"range\": [0, 1, 2]}}"),
            "E0109");
  one_error(spec(", {\"name\": \"x\", \"rgba\": [1, 1, 1], \"geometry\": {\"sphere\": {\"radius\": 1}}, "
                 "\"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"),
            "E0109");
  Diagnostic d = one_error(spec(", {\"name\": \"x\", \"rgba\": [1, 1, 1.5, 1], \"geometry\": "
                                "{\"sphere\": {\"radius\": 1}}, \"joint\": {\"type\": \"fixed\", \"parent\": \"base\"}}"),
                           "E0110");
  EXPECT_EQ(d.pointer, "/parts/1/rgba/2");
  one_error(spec("", "{\"name\": \"f\", \"receptor\": \"a\", \"effector\": \"b\", "
                     "\"mapping\": {\"type\": \"binary\"}, \"effect\": {\"type\": \"illumination\", "
                     "\"color\": [255, 0, 0]}}"),
            "E0110");
}

// ---------------------------------------------------------------- mesh paths
class MeshPaths : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("efc_reader_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
           "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir / "meshes");
    std::ofstream(dir / "meshes" / "a.OBJ") << "v 0 0 0\n";
    std::ofstream(dir / "meshes" / "b.stl") << "solid\n";
  }
  void TearDown() override { fs::remove_all(dir); }
  Result with_mesh(const std::string& path, ReadOptions opts = {}) {
    std::string text = "{\"efc\": 1, \"name\": \"a\", \"parts\": [{\"name\": \"b\", "
                       "\"geometry\": {\"mesh\": " +
                       nlohmann::json(path).dump() + ", \"scale\": [2, 2, 2]}}]}";
    return read(text, opts, dir.string());
  }
  fs::path dir;
};

TEST_F(MeshPaths, RelativeInsideResolves) {
  for (const char* p : {"meshes/a.OBJ", "./meshes/b.stl", "meshes/../meshes/a.OBJ"}) {
    Result r = with_mesh(p);
    ASSERT_TRUE(r.obj) << p;
    const Geometry& g = r.obj->parts[0].geometry;
    EXPECT_EQ(g.mesh_path, p);
    EXPECT_TRUE(fs::path(g.mesh_resolved).is_absolute());
    EXPECT_TRUE(fs::equivalent(g.mesh_resolved, dir / fs::path(p)));
    EXPECT_EQ(g.scale, (Vec3{2, 2, 2}));
  }
}

TEST_F(MeshPaths, Escapes) {
  for (const char* p : {"../a.obj", "meshes/../../a.obj", "./../x/a.obj"}) {
    Result r = with_mesh(p);
    EXPECT_FALSE(r.obj);
    EXPECT_EQ(codes(r.diags), std::vector<std::string>{"E0112"}) << p;
  }
}

TEST_F(MeshPaths, Absolute) {
  std::string abs = (dir / "meshes" / "b.stl").string();
  Result r = with_mesh(abs);
  EXPECT_EQ(codes(r.diags), std::vector<std::string>{"E0113"});
  ReadOptions allow;
  allow.allow_absolute_paths = true;
  r = with_mesh(abs, allow);
  ASSERT_TRUE(r.obj);
  EXPECT_EQ(r.obj->parts[0].geometry.mesh_resolved, abs);
}

TEST_F(MeshPaths, ExtensionAndExistence) {
  EXPECT_EQ(codes(with_mesh("meshes/a.fbx").diags), std::vector<std::string>{"E0114"});
  EXPECT_EQ(codes(with_mesh("meshes/a").diags), std::vector<std::string>{"E0114"});
  EXPECT_EQ(codes(with_mesh("").diags), std::vector<std::string>{"E0114"});
  Result r = with_mesh("meshes/missing.ply");
  ASSERT_EQ(codes(r.diags), std::vector<std::string>{"E0115"});
  EXPECT_NE(r.diags.items()[0].message.find("missing.ply"), std::string::npos);
  EXPECT_EQ(codes(with_mesh("meshes").diags), std::vector<std::string>{"E0114"});
  EXPECT_EQ(codes(with_mesh("meshes/dir.obj/").diags).size(), 1u);
}

// Every prefix of a valid spec, and the spec with each byte replaced by a
// troublesome one: never a crash, and a cut document is always an error.
TEST(Malformed, PrefixesAndMutationsNeverCrash) {
  const std::string full = kLamp;
  for (size_t n = 0; n < full.size(); ++n) {
    Result r = read(full.substr(0, n));
    EXPECT_FALSE(r.obj) << n;
    EXPECT_TRUE(r.diags.has_errors()) << n;
  }
  for (size_t i = 0; i < full.size(); ++i) {
    for (char c : {'"', '{', ']', ',', '\\', '\0', '\xff', '9'}) {
      std::string m = full;
      m[i] = c;
      Result r = read(m);
      if (r.obj) {
        Diagnostics d;
        check_structure(*r.obj, d);
        check_resolved(*r.obj, d);
      }
    }
  }
}

// ---------------------------------------------------------------- whole runs
TEST(Reader, ReportsEveryProblemInFileOrder) {
  const char* text = R"({
  "efc": 1,
  "name": "three_errors",
  "parts": [
    {"name": "base", "geometry": {"box": {"size": [1, 1]}}},
    {"name": "a b", "geometry": {"sphere": {"radius": 1}},
     "joint": {"type": "revolute", "parent": "base", "range": [0, 1], "colour": 1}}
  ]
})";
  Result r = read(text);
  EXPECT_FALSE(r.obj);
  ASSERT_EQ(codes(r.diags), (std::vector<std::string>{"E0109", "E0105", "E0103"}));
  EXPECT_EQ(r.diags.items()[0].line, 5);
  EXPECT_EQ(r.diags.items()[1].line, 6);
  EXPECT_EQ(r.diags.items()[2].line, 7);
  EXPECT_EQ(r.diags.items()[2].col, 71);
  EXPECT_EQ(r.diags.items()[2].pointer, "/parts/1/joint/colour");
  EXPECT_EQ(r.diags.items()[2].file, "spec.json");
}

TEST(ReadFile, MissingFileIsAnIoError) {
  Diagnostics d;
  bool io = false;
  auto obj = read_json_file("/nonexistent/efc/spec.json", {}, d, &io);
  EXPECT_FALSE(obj);
  EXPECT_TRUE(io);
  EXPECT_EQ(codes(d), std::vector<std::string>{"E0001"});
  d.clear();
  obj = read_json_file(fs::temp_directory_path().string(), {}, d, &io);
  EXPECT_TRUE(io);
  EXPECT_EQ(codes(d), std::vector<std::string>{"E0001"});
}

TEST(ReadFile, SetsFileAndBaseDir) {
  fs::path dir = fs::temp_directory_path() / "efc_reader_test_file";
  fs::create_directories(dir);
  std::ofstream(dir / "s.json") << spec();
  Diagnostics d;
  bool io = true;
  auto obj = read_json_file((dir / "s.json").string(), {}, d, &io);
  ASSERT_TRUE(obj);
  EXPECT_FALSE(io);
  EXPECT_EQ(obj->file, (dir / "s.json").string());
  EXPECT_EQ(obj->base_dir, dir.string());
  // A syntax error is input error, not I/O.
  std::ofstream(dir / "bad.json") << "{";
  obj = read_json_file((dir / "bad.json").string(), {}, d, &io);
  EXPECT_FALSE(obj);
  EXPECT_FALSE(io);
  EXPECT_EQ(d.items().back().file, (dir / "bad.json").string());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace efc
