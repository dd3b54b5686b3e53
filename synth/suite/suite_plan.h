// The plan of `efc synth-suite -o DIR --count N --seed S`: which sequences the
// perception benchmark holds, each with its object (a spec v1 document), the
// function it is about, its motion profile, scene knobs and seed.
//
// Coverage. The first 20 entries (when count >= 20) cover the 20 mapping x
// effect pairs once each, in a seed-dependent order; their receptor joints
// cycle revolute, prismatic, continuous (continuous only with step, linear
// and cumulative: see function_pairs.h; binary falls back to revolute), and
// every fourth entry (i % 4 == 1) and some others ask for a small receptor
// (examples' receptors are measured; most are small). About a third
// of them vary an example that has the pair with that joint type; the rest
// are generated (generated_object.h). Beyond 20, pairs are drawn uniformly
// and 60 % of entries vary an example when one has the pair.
//
// Determinism. Entry i depends only on (seed, i) and the examples folder's
// contents: plan_suite(20, s) is a prefix of plan_suite(40, s), and a seed
// gives the same bytes (spec_json included) with every standard library
// (suite_rng.h).
//
// Files. The caller writes entry.spec_json to DIR/<name>/spec.json and copies
// each of entry.files_to_copy (absolute source -> path relative to that
// folder); example specs keep their relative mesh paths ("meshes/x.obj"), so
// the folder is self-contained and loads without --allow-absolute-paths.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "synth/suite/knobs.h"

namespace efc::synth {

struct SuiteEntry {
  std::string name;       // "s0007_linear-temperature_revolute": unique, [a-z0-9_-]
  std::string origin;     // "example:stove" or "generated"
  std::string spec_json;  // the spec document (valid spec v1; passes efc check)
  std::string object;     // the spec's "name"
  // The function the sequence is about (a name in the spec), its parts, and
  // its template: "linear", "temperature", receptor joint "revolute".
  std::string function, receptor, effector;
  std::string mapping, effect, receptor_joint;
  bool small_receptor = false;  // the receptor's largest size is at most 5 cm
  uint64_t seed = 0;            // the sequence's own seed (camera jitter, noise)
  std::string profile;          // for efc synth --profile: press:2 or press:3 (scene_draw.h)
  SceneKnobs knobs;  // knobs.object_scale: the scale applied to an example (1 when generated)
  // (absolute source path, path relative to the spec's folder) of each mesh.
  std::vector<std::pair<std::string, std::string>> files_to_copy;
};

// The largest receptor size counted as small (m): a knob of 2.5 cm radius.
constexpr double kSmallReceptorSize = 0.05;

// N entries from `seed`. examples_dir is the folder of example specs
// (examples/); empty means generated objects only. forced_noise, when not
// null, is every entry's noise level (the other knobs are drawn as without
// it). Returns an empty list with *error set when the examples cannot be
// read or count is negative.
std::vector<SuiteEntry> plan_suite(int count, uint64_t seed, const std::string& examples_dir,
                                   const NoiseLevel* forced_noise, std::string* error);

// The entry's line of DIR/index.json; "spec" is "<name>/spec.json", the
// layout above.
nlohmann::json entry_to_json(const SuiteEntry& entry);

}  // namespace efc::synth
