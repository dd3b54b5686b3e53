// DATASET/dataset_metadata.json: a list with one entry per video, naming
// every other file of that video by a path relative to DATASET (the
// reference loader's root_path).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "compiler/diagnostics.h"
#include "pipeline/egofun3d/json_doc.h"

namespace efc::egofun3d {

struct VideoEntry {
  std::string pointer;  // "/3": where the entry sits in dataset_metadata.json
  std::string video_name, folder, source;
  nlohmann::json function_instance_id;  // a number or a string, as the files have it
  // Full paths (DATASET joined with the entry's relative path).
  std::string video, extrinsics, intrinsics, masks, geometry, part_annotation, articulation, function_annotation;
  std::string geometry_type;
  bool cropped_video = false;  // video from cropped_video_path (EgoExo4D crops)
  bool ok = true;              // false: the entry itself is wrong (already reported)
};

// E1040 for a missing or malformed index; entries with a missing or
// ill-typed key are reported and kept with ok = false, so the others still
// import. Two entries whose folders collide: the second is not ok. Returns
// false when the index as a whole is unusable (no list).
bool read_dataset_index(const std::string& dataset_dir, Diagnostics& diags, JsonDoc* doc,
                        std::vector<VideoEntry>* out);

// "3" for 3, "abc" for "abc": function_instance_id compared as text, since
// some files write it as a number and others as a string.
std::string id_text(const nlohmann::json& id);

}  // namespace efc::egofun3d
