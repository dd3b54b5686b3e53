// `efc infer SEQ -o OUT`: a recording of someone operating an object in, a
// spec v1 out (shared/spec/cli.md). The stages, each its own file:
//   observations   masks x depth x poses -> each part's points per frame
//   ego_motion     the camera poses registered onto the static parts
//   part_tracking  each other part's motion by robust point-to-plane ICP
//   joint_estimate its joint from that motion and the hand's (BIC, fused)
//   reconstruction its points fused at q = 0, a closed mesh
//   templates      each function's effect, mapping and parameters
//                  (pipeline/templates)
//   spec_assembly  the spec, in an object frame z-up against gravity, with
//                  x-efc-object-to-world
// Every stage reports its time, residuals and confidence into report.json.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

#include "compiler/diagnostics.h"
#include "pipeline/cloud/mesh.h"
#include "pipeline/infer/observations.h"
#include "pipeline/templates/template_input.h"

namespace efc::pipeline {

struct InferOptions {
  ObserveOptions observe;
  TemplateOptions templates;
  bool use_hands = true;  // false: the hand track is ignored (to measure what it buys)
  ProgressFn progress;
};

struct InferResult {
  nlohmann::ordered_json spec;
  nlohmann::ordered_json report;
  std::vector<std::pair<std::string, TriMesh>> meshes;  // "meshes/<part>.obj" -> mesh (object frame)
};

// Exit codes as the CLI's: 0 ok, 1 the sequence cannot give a spec
// (diagnostics say why), 2 a file could not be read.
int infer_sequence(const std::string& sequence_dir, const InferOptions& options, Diagnostics& diags,
                   InferResult* result);

// Writes OUT/spec.json, OUT/meshes/, OUT/report.json, all or nothing: built
// in a sibling folder, checked with the compiler's load_spec (an inferred
// spec that would not compile is never written), then renamed into place.
// An existing OUT is replaced only when it holds an earlier infer output.
int write_infer_output(const InferResult& result, const std::string& out_dir, Diagnostics& diags);

}  // namespace efc::pipeline
