// One video of the dataset to one sequence folder (see importer.h): reads
// and checks every annotation file before decoding anything, then decodes
// the video into rgb/, crops and writes the masks, writes poses.txt,
// meta.json and truth/, checks the truth spec with the compiler and the
// folder with the sequence checks, and renames it into place.
#pragma once

#include <string>

#include "compiler/diagnostics.h"
#include "pipeline/egofun3d/dataset_index.h"
#include "pipeline/egofun3d/json_doc.h"

namespace efc::egofun3d {

struct VideoResult {
  bool ok = false;
  bool io_failure = false;  // the output could not be written (exit 2)
  std::string summary;      // "120 frames 640x480, parts: knob, burner -> DIR/kitchen_01"
};

VideoResult import_video(const VideoEntry& entry, const JsonDoc& index, const std::string& output_dir,
                         Diagnostics& diags);

}  // namespace efc::egofun3d
