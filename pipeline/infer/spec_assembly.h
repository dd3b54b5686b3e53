// efc infer, last stage: the spec v1 document. The root is the static part
// seen best (role base); every other part hangs from it by its estimated
// joint. Geometry is the reconstructed mesh (object frame, q = 0), masses
// are left to the compiler (the mesh's volume at its default density).
// Functions whose receptor was found not to move cannot be compiled (a
// receptor must be movable): they are left out with a warning rather than
// given an invented joint.
#pragma once

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "pipeline/infer/joint_estimate.h"
#include "pipeline/templates/template_input.h"

namespace efc::pipeline {

struct AssembledPart {
  std::string name;       // a valid spec name
  std::string role;       // meta.json's role
  bool root = false;
  JointEstimate joint;    // ignored for the root
  std::string mesh;       // "meshes/<name>.obj"
  std::string parent;     // the root's name
};

// A name the spec accepts (^[A-Za-z_][A-Za-z0-9_]{0,63}$) made from any text.
std::string spec_name(const std::string& text);

nlohmann::ordered_json assemble_spec(const std::string& object_name, const std::string& description,
                                     const std::vector<AssembledPart>& parts,
                                     const std::vector<InferredFunction>& functions,
                                     const Eigen::Isometry3d& object_to_world, const std::string& meta_file,
                                     Diagnostics& diags);

}  // namespace efc::pipeline
