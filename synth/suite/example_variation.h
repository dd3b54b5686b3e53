// Example-based suite objects: the hand-written examples (examples/*.json),
// randomised so that no two sequences show the same object.
//
// A variation keeps the example's structure (parts, joints, functions, mesh
// files) and changes its numbers consistently:
//   - a uniform scale s (0.75-1.3, narrowed so the object's largest size stays
//     within 0.1-1.2 m, or at most its own when it is larger) of every
//     geometry, mesh `scale`, joint origin, effect position, emitter, outlet
//     and airflow reach; masses by s^3;
//   - every bounded joint's range scaled about 0 (revolute by 0.7-1.1,
//     prismatic by s times 0.75-1.15), so the drawn pose (position 0) stays
//     where it was; initial positions, spring rests, thresholds, hysteresis
//     and geometry-effect targets follow their joint, and linear gains are
//     re-expressed per new unit;
//   - each effect's quantity rescaled (illumination, fluid, airflow by a
//     factor; temperature about 20 C): range, linear offset, cumulative
//     delta and initial follow;
//   - thresholds of receptors the hand moves shifted within 15-85 % of the
//     new range (a chained receptor, moved by another function, keeps its
//     point so the chain still fires), some gains and deltas jittered,
//     colours and time constants jittered;
//   - the description says so (the example's text names its old numbers).
// The result passes the same checks as the example.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "synth/suite/spec_json.h"
#include "synth/suite/suite_rng.h"

namespace efc::synth::suite {

struct ExampleSpec {
  std::string name;  // the file's stem: "stove"
  std::string dir;   // the examples folder; mesh paths are relative to it
  SpecJson doc;
};

// Every *.json file of `dir`, by file name. False with *error naming the file
// when the folder or a file cannot be read, a file is not a spec document, or
// it cannot be varied (a mesh that cannot be read, a path out of the folder).
bool load_examples(const std::string& dir, std::vector<ExampleSpec>* out, std::string* error);

// A function of an example that a suite entry can be about: its receptor is
// moved by the hand, not by another function (a chain's later links are
// still shown, but an entry names the link the hand drives). Examples with a
// movable part enclosed in another part's box (never in view) give none.
struct ExampleFunction {
  size_t example = 0;  // index into the examples
  std::string function, receptor, effector;
  std::string mapping, effect, receptor_joint;
};
std::vector<ExampleFunction> operable_functions(const std::vector<ExampleSpec>& examples);

struct VariedExample {
  SpecJson spec;
  double scale = 1;
  // Mesh files the spec names: (absolute source, path relative to the spec's
  // folder, exactly as the spec writes it).
  std::vector<std::pair<std::string, std::string>> files;
};

// False with *error when a mesh of the example cannot be read or its path
// leaves the examples folder.
bool vary_example(const ExampleSpec& example, SuiteRng& rng, VariedExample* out,
                  std::string* error);

}  // namespace efc::synth::suite
