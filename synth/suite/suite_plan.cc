#include "synth/suite/suite_plan.h"

#include <cmath>
#include <cstdio>

#include "synth/suite/example_variation.h"
#include "synth/suite/function_pairs.h"
#include "synth/suite/generated_object.h"
#include "synth/suite/geometry_bounds.h"
#include "synth/suite/scene_draw.h"

namespace efc::synth {
namespace {

using suite::derive_seed;
using suite::SpecJson;
using suite::SuiteRng;

// The independent random streams of an entry: changing how one aspect is
// drawn leaves the others as they were.
enum Stream : uint64_t { kCoverage = 1, kChoice, kSpec, kKnobs, kSequence };

constexpr int kCoveredPairs = 20;

// What an entry shows before its object is built.
struct EntryChoice {
  suite::FunctionPair pair;
  std::string joint;  // for a generated object
  bool small = false;
  const suite::ExampleFunction* example = nullptr;  // null: generated
};

std::vector<const suite::ExampleFunction*> candidates(
    const std::vector<suite::ExampleFunction>& functions, const suite::FunctionPair& pair,
    const std::string& joint) {
  std::vector<const suite::ExampleFunction*> out;
  for (const auto& f : functions)
    if (f.mapping == pair.mapping && f.effect == pair.effect &&
        (joint.empty() || f.receptor_joint == joint))
      out.push_back(&f);
  return out;
}

EntryChoice choose(int i, const std::vector<suite::FunctionPair>& coverage_order,
                   const std::vector<suite::ExampleFunction>& functions, SuiteRng& rng) {
  EntryChoice c;
  const auto& joints = suite::receptor_joint_types();
  if (i < kCoveredPairs) {
    c.pair = coverage_order[i];
    c.joint = joints[i % 3];
    if (c.joint == "continuous" && !suite::continuous_receptor_allowed(c.pair.mapping))
      c.joint = "revolute";
    c.small = i % 4 == 1 || rng.chance(0.15);
    const auto matching = candidates(functions, c.pair, c.joint);
    if (!matching.empty() && rng.chance(0.35)) c.example = rng.pick(matching);
    return c;
  }
  c.pair = rng.pick(suite::all_function_pairs());
  const auto matching = candidates(functions, c.pair, "");
  if (!matching.empty() && rng.chance(0.6)) {
    c.example = rng.pick(matching);
    return c;
  }
  c.joint = joints[rng.weighted({0.45, 0.35, 0.2})];
  if (c.joint == "continuous" && !suite::continuous_receptor_allowed(c.pair.mapping))
    c.joint = "revolute";
  c.small = rng.chance(0.3);
  return c;
}

bool receptor_is_small(const SpecJson& spec, const std::string& receptor,
                       const std::string& base_dir) {
  for (const auto& p : spec["parts"]) {
    if (p["name"] != receptor) continue;
    suite::Bounds b;
    std::string ignored;  // the example's meshes were measured once already
    return suite::add_geometry_bounds(p["geometry"], base_dir, &b, &ignored) &&
           b.max_extent() <= kSmallReceptorSize;
  }
  return false;
}

// Which side face the receptor is on: +1 the right (+x), -1 the left, 0 the
// front or top. Its centre beyond 90 % of the base's half width, and not
// on the front, puts it on a side.
int receptor_side(const SpecJson& spec, const std::string& receptor, const std::string& base_dir) {
  suite::Bounds base, part;
  std::string ignored;
  for (const auto& p : spec["parts"]) {
    if (p["name"] == receptor) suite::add_geometry_bounds(p["geometry"], base_dir, &part, &ignored);
    else if (!p.contains("joint")) suite::add_geometry_bounds(p["geometry"], base_dir, &base, &ignored);
  }
  if (base.empty() || part.empty()) return 0;
  const double cx = 0.5 * (part.lo[0] + part.hi[0]), cy = 0.5 * (part.lo[1] + part.hi[1]);
  const double bx = 0.5 * (base.lo[0] + base.hi[0]), hx = 0.5 * (base.hi[0] - base.lo[0]);
  const double front = base.lo[1] + 0.1 * (base.hi[1] - base.lo[1]);
  if (hx <= 0 || cy < front) return 0;
  if (cx > bx + 0.9 * hx) return 1;
  if (cx < bx - 0.9 * hx) return -1;
  return 0;
}

std::string entry_name(int i, const SuiteEntry& e) {
  char index[16];
  std::snprintf(index, sizeof index, "s%04d", i);
  return std::string(index) + "_" + e.mapping + "-" + e.effect + "_" + e.receptor_joint;
}

bool plan_entry(int i, uint64_t seed, const std::vector<suite::FunctionPair>& coverage_order,
                const std::vector<suite::ExampleSpec>& examples,
                const std::vector<suite::ExampleFunction>& functions,
                const NoiseLevel* forced_noise, SuiteEntry* e, std::string* error) {
  SuiteRng choice_rng(derive_seed(seed, i, kChoice));
  const EntryChoice c = choose(i, coverage_order, functions, choice_rng);

  SuiteRng spec_rng(derive_seed(seed, i, kSpec));
  SpecJson spec;
  std::string base_dir;
  double object_scale = 1;
  if (c.example) {
    const suite::ExampleSpec& example = examples[c.example->example];
    suite::VariedExample varied;
    if (!suite::vary_example(example, spec_rng, &varied, error)) {
      *error = example.name + ": " + *error;
      return false;
    }
    spec = std::move(varied.spec);
    e->files_to_copy = std::move(varied.files);
    object_scale = varied.scale;
    base_dir = example.dir;
    e->origin = "example:" + example.name;
    e->function = c.example->function;
    e->receptor = c.example->receptor;
    e->effector = c.example->effector;
    e->receptor_joint = c.example->receptor_joint;
  } else {
    suite::GeneratedObject g =
        suite::generate_object({c.pair.mapping, c.pair.effect, c.joint, c.small}, spec_rng);
    spec = std::move(g.spec);
    e->origin = "generated";
    e->function = g.function;
    e->receptor = g.receptor;
    e->effector = g.effector;
    e->receptor_joint = c.joint;
  }
  e->mapping = c.pair.mapping;
  e->effect = c.pair.effect;
  e->object = spec["name"].get<std::string>();
  e->small_receptor = receptor_is_small(spec, e->receptor, base_dir);
  e->spec_json = spec.dump(2) + "\n";

  SuiteRng knob_rng(derive_seed(seed, i, kKnobs));
  e->knobs = suite::draw_scene_knobs(knob_rng, forced_noise);
  e->knobs.object_scale = object_scale;
  // Someone operating a knob on the object's side stands to that side: the
  // camera's azimuth (drawn within +-0.7 rad of the front) moves to 0.55-0.85
  // rad towards it, so the side face is seen at an angle. Otherwise a
  // recording may never show the receptor it is about.
  if (const int side = receptor_side(spec, e->receptor, base_dir))
    e->knobs.camera_azimuth = side * (0.55 + 0.3 * std::abs(e->knobs.camera_azimuth) / 0.7);
  e->profile = suite::draw_profile(knob_rng);
  e->seed = derive_seed(seed, i, kSequence);
  e->name = entry_name(i, *e);
  return true;
}

}  // namespace

std::vector<SuiteEntry> plan_suite(int count, uint64_t seed, const std::string& examples_dir,
                                   const NoiseLevel* forced_noise, std::string* error) {
  error->clear();
  if (count < 0) {
    *error = "the suite's count must be 0 or more (got " + std::to_string(count) + ")";
    return {};
  }
  std::vector<suite::ExampleSpec> examples;
  if (!examples_dir.empty() && !suite::load_examples(examples_dir, &examples, error)) return {};
  const std::vector<suite::ExampleFunction> functions = suite::operable_functions(examples);

  // One order of the 20 pairs per seed, shared by the first 20 entries.
  std::vector<suite::FunctionPair> coverage_order = suite::all_function_pairs();
  SuiteRng coverage_rng(derive_seed(seed, 0, kCoverage));
  coverage_rng.shuffle(coverage_order);

  std::vector<SuiteEntry> entries(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i)
    if (!plan_entry(i, seed, coverage_order, examples, functions, forced_noise, &entries[i], error))
      return {};
  return entries;
}

nlohmann::json entry_to_json(const SuiteEntry& e) {
  nlohmann::json files = nlohmann::json::array();
  for (const auto& f : e.files_to_copy) files.push_back(f.second);
  return {{"name", e.name},
          {"spec", e.name + "/spec.json"},
          {"origin", e.origin},
          {"object", e.object},
          {"function", e.function},
          {"receptor", e.receptor},
          {"effector", e.effector},
          {"mapping", e.mapping},
          {"effect", e.effect},
          {"receptor_joint", e.receptor_joint},
          {"small_receptor", e.small_receptor},
          {"seed", e.seed},
          {"profile", e.profile},
          {"knobs", to_json(e.knobs)},
          {"files", files}};
}

}  // namespace efc::synth
