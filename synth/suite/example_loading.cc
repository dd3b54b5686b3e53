// load_examples() and operable_functions() of example_variation.h.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "synth/suite/example_variation.h"
#include "synth/suite/geometry_bounds.h"

namespace efc::synth::suite {
namespace {

namespace fs = std::filesystem;

bool is_string(const SpecJson& o, const char* key) { return o.contains(key) && o[key].is_string(); }

bool has_typed_object(const SpecJson& o, const char* key) {
  return o.contains(key) && o[key].is_object() && is_string(o[key], "type");
}

// The fields the suite reads must have the right JSON types; everything else
// is the loader's business (the test loads every varied example).
std::string shape_problem(const SpecJson& doc) {
  if (!doc.is_object()) return "not a JSON object";
  if (!is_string(doc, "name")) return "no \"name\"";
  if (!doc.contains("parts") || !doc["parts"].is_array()) return "no \"parts\" array";
  for (const auto& p : doc["parts"]) {
    if (!p.is_object() || !is_string(p, "name")) return "a part without a name";
    if (!p.contains("geometry") || !p["geometry"].is_object()) return "a part without geometry";
    if (p.contains("joint") && !has_typed_object(p, "joint")) return "a joint without a type";
  }
  if (!doc.contains("functions")) return "";
  if (!doc["functions"].is_array()) return "\"functions\" is not an array";
  for (const auto& f : doc["functions"]) {
    if (!f.is_object() || !is_string(f, "name") || !is_string(f, "receptor") ||
        !is_string(f, "effector") || !has_typed_object(f, "mapping") ||
        !has_typed_object(f, "effect"))
      return "a function without name, receptor, effector, mapping type or effect type";
  }
  return "";
}

std::string joint_type_of(const SpecJson& doc, const std::string& part) {
  for (const auto& p : doc["parts"])
    if (p["name"] == part && p.contains("joint")) return p["joint"]["type"].get<std::string>();
  return "";
}

// Whether a movable part of the example lies wholly inside a box of another
// part (the toaster's carriage in its body, the toilet's flapper in its
// tank): no camera ever sees it, so no recording can show its joint, and a
// benchmark entry would score the method on what it cannot observe. Only
// axis-aligned boxes count as enclosures (a box's bounds are the box; a
// cylinder's are not the cylinder). Meshes are not enclosures.
bool has_enclosed_moving_part(const ExampleSpec& e) {
  std::string ignored;
  for (const auto& p : e.doc["parts"]) {
    if (!p.contains("joint") || p["joint"]["type"] == "fixed") continue;
    Bounds moving;
    if (!add_geometry_bounds(p["geometry"], e.dir, &moving, &ignored) || moving.empty()) continue;
    for (const auto& q : e.doc["parts"]) {
      if (q["name"] == p["name"]) continue;
      std::vector<SpecJson> primitives;
      if (q["geometry"].contains("compound") && q["geometry"]["compound"].is_array())
        for (const auto& g : q["geometry"]["compound"]) primitives.push_back(g);
      else
        primitives.push_back(q["geometry"]);
      for (const SpecJson& g : primitives) {
        if (!g.is_object() || !g.contains("box") || g["box"].contains("rpy") || g["box"].contains("quat")) continue;
        Bounds box;
        if (!add_geometry_bounds(g, e.dir, &box, &ignored) || box.empty()) continue;
        bool inside = true;
        for (int k = 0; k < 3; ++k)
          inside = inside && box.lo[k] <= moving.lo[k] + 1e-6 && moving.hi[k] <= box.hi[k] + 1e-6;
        if (inside) return true;
      }
    }
  }
  return false;
}

}  // namespace

bool load_examples(const std::string& dir, std::vector<ExampleSpec>* out, std::string* error) {
  out->clear();
  std::error_code ec;
  const fs::path folder = fs::absolute(dir, ec);
  if (ec || !fs::is_directory(folder, ec)) {
    *error = "examples folder '" + dir + "' cannot be read";
    return false;
  }
  std::vector<fs::path> files;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".json" && it->is_regular_file(ec)) files.push_back(it->path());
  if (ec) {
    *error = "examples folder '" + dir + "' cannot be listed: " + ec.message();
    return false;
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    ExampleSpec e;
    e.name = file.stem().string();
    e.dir = folder.string();
    e.doc = SpecJson::parse(text.str(), nullptr, /*allow_exceptions=*/false);
    const std::string problem = e.doc.is_discarded() ? "not valid JSON" : shape_problem(e.doc);
    if (!in || !problem.empty()) {
      *error = file.string() + ": " + (in ? problem : "cannot be read");
      return false;
    }
    // A dry run: an example that cannot be varied (a mesh that cannot be
    // read, a path out of the folder) is reported now, whatever the seed.
    SuiteRng dry_run(0);
    VariedExample unused;
    if (!vary_example(e, dry_run, &unused, error)) {
      *error = file.string() + ": " + *error;
      return false;
    }
    out->push_back(std::move(e));
  }
  return true;
}

std::vector<ExampleFunction> operable_functions(const std::vector<ExampleSpec>& examples) {
  std::vector<ExampleFunction> out;
  for (size_t i = 0; i < examples.size(); ++i) {
    const SpecJson& doc = examples[i].doc;
    if (!doc.contains("functions") || has_enclosed_moving_part(examples[i])) continue;
    std::set<std::string> moved_by_functions;
    for (const auto& f : doc["functions"])
      if (f["effect"]["type"] == "geometry")
        moved_by_functions.insert(f["effector"].get<std::string>());
    for (const auto& f : doc["functions"]) {
      ExampleFunction ef;
      ef.example = i;
      ef.function = f["name"].get<std::string>();
      ef.receptor = f["receptor"].get<std::string>();
      ef.effector = f["effector"].get<std::string>();
      ef.mapping = f["mapping"]["type"].get<std::string>();
      ef.effect = f["effect"]["type"].get<std::string>();
      ef.receptor_joint = joint_type_of(doc, ef.receptor);
      if (moved_by_functions.count(ef.receptor) || ef.receptor_joint.empty() ||
          ef.receptor_joint == "fixed")
        continue;
      out.push_back(ef);
    }
  }
  return out;
}

}  // namespace efc::synth::suite
