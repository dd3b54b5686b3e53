// The three annotation files of a video, each holding many function
// instances of which the video shows one (its function_instance_id):
//   part_annotation_path      [{function_instance_id, receptor: {label, indices, pid},
//                               effector: {...}, description}] (or an object keyed by id,
//                               optionally with "remove": {"remove": {"indices": [...]}},
//                               vertices that belong to no part, not even the base)
//   articulation_path         [{pid, type, axis, origin, rangeMin, rangeMax}]
//   function_annotation_path  [{function_instance_id, physics, func}]
// Every problem is E1046 at the value's line:col.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compiler/diagnostics.h"
#include "pipeline/egofun3d/json_doc.h"

namespace efc::egofun3d {

struct PartAnnotation {
  std::string label;
  std::vector<long long> indices;  // into the PLY's vertices (checked by the spec builder)
  nlohmann::json pid;
  std::string pointer;  // where it sits in the part annotation file
};

struct FunctionInstance {
  PartAnnotation receptor, effector;
  std::vector<long long> removed;
  std::string file;  // the part annotation file, for messages
};

// One joint, its type mapped to the spec's: revolute (also "rotation",
// "hinge"), prismatic ("translation", "slider"), continuous, fixed
// ("static", "none").
struct JointAnnotation {
  bool found = false;  // false: the file has no entry for the pid (the part is fixed)
  std::string type;
  std::array<double, 3> axis{0, 0, 1}, origin{0, 0, 0};
  double lo = 0, hi = 0;
  bool degrees = false;  // a revolute range beyond 2 pi was read as degrees (and converted)
  std::string file, pointer;
};

struct FunctionAnnotation {
  std::string physics, func;  // lower case: geometry|illumination|temperature|fluid|airflow, binary|step|linear|cumulative
};

// `vertex_count`: the PLY's, to check every index against (at its line:col);
// negative to skip the check (the PLY itself could not be read).
bool read_function_instance(const std::string& path, const nlohmann::json& id, long long vertex_count,
                            Diagnostics& diags, FunctionInstance* out);
// The entries for both pids, read in one pass over the file.
bool read_articulations(const std::string& path, const nlohmann::json& receptor_pid,
                        const nlohmann::json& effector_pid, Diagnostics& diags, JointAnnotation* receptor,
                        JointAnnotation* effector);
bool read_function_annotation(const std::string& path, const nlohmann::json& id, Diagnostics& diags,
                              FunctionAnnotation* out);

}  // namespace efc::egofun3d
