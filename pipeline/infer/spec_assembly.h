// efc infer, last stage: the spec v1 document. The root is the static part
// seen best (role base); every other part hangs from it by its estimated
// joint. Geometry is the reconstructed mesh (object frame, q = 0), masses
// are left to the compiler (the mesh's volume at its default density).
// Functions whose receptor was found not to move cannot be compiled (a
// receptor must be movable): they are left out with a warning rather than
// given an invented joint. A function whose effector was never seen (so
// never reconstructed) keeps its template (read from the names): the
// effector stands in as a small sphere fixed to the root, with a warning
// (E1066), unless its effect moves it (geometry: it is left out).
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

// Parts that could not be reconstructed (E1058): the effectors among them
// that a kept function needs stand in as a sphere of kStandInRadius at
// `centre` (object frame, q = 0; the root's middle: where it is, nothing
// says), fixed to the root.
struct StandIns {
  std::vector<std::string> names;  // valid spec names
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};
constexpr double kStandInRadius = 0.01;  // m

// A name the spec accepts (^[A-Za-z_][A-Za-z0-9_]{0,63}$) made from any text.
std::string spec_name(const std::string& text);

nlohmann::ordered_json assemble_spec(const std::string& object_name, const std::string& description,
                                     const std::vector<AssembledPart>& parts,
                                     const std::vector<InferredFunction>& functions,
                                     const StandIns& unseen, const Eigen::Isometry3d& object_to_world,
                                     const std::string& meta_file, Diagnostics& diags);

}  // namespace efc::pipeline
