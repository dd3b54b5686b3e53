// truth/spec.json from the annotations: the geometry split into parts by the
// annotated vertex indices, the annotated joints, and the one function the
// video shows. The PLY is in the world frame of the extrinsics, so the spec
// is too (truth/object_pose.json is the identity).
//
//   receptor, effector  their vertices (the part annotation's indices); a
//                       mesh of the faces whose corners all belong to the
//                       part, or, without faces (a point cloud), a box
//                       fitted to the points' bounds
//   base                every other vertex (less "remove"), the root
//   joints              the articulation entry with the part's pid, parent
//                       the base; no entry: fixed (and a note)
//   function            f<function_instance_id>: mapping `func` and effect
//                       `physics` with the spec's defaults (cumulative gets
//                       delta = a quarter of the effect's range, the one
//                       value the spec does not default)
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/egofun3d/annotations.h"
#include "pipeline/egofun3d/ply.h"

namespace efc::egofun3d {

struct TruthInput {
  std::string object_name;  // a valid spec name
  std::string receptor_name, effector_name, base_name, function_name;
  const Ply* ply = nullptr;
  const FunctionInstance* instance = nullptr;
  JointAnnotation receptor_joint, effector_joint;
  FunctionAnnotation function;
  nlohmann::json provenance;  // kept as "x-egofun3d"
};

struct TruthSpec {
  nlohmann::json spec;
  std::vector<std::pair<std::string, std::string>> meshes;  // "meshes/<part>.obj" -> OBJ text
  std::vector<std::string> notes;  // what was assumed (boxes for point clouds, defaults), for the user
};

TruthSpec build_truth_spec(const TruthInput& in);

}  // namespace efc::egofun3d
