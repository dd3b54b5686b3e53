// Writing a backend's outputs: one helper for every target.
#pragma once

#include <string>
#include <vector>

#include "compiler/diagnostics.h"

namespace efc {

// One file of a target's output, generated in memory before anything is
// written: its path relative to the target folder ("meshes/a.stl") and bytes.
struct OutputFile {
  std::string path;
  std::string bytes;
};

// Writes `text` to `path` (binary, so line endings are exactly as generated).
// False with the reason in *error (the system's message) on failure.
bool write_text_file(const std::string& path, const std::string& text, std::string* error);

// Whether `path` stays inside the folder it is relative to: not empty, not
// absolute, no "." or ".." component, no empty component, no backslash or
// control character. Every generated path must be one.
bool is_contained_path(const std::string& path);

// Writes every file under `dir` (which exists), creating the subfolders their
// paths name. False after adding an E0900 error naming the file (also for a
// path that is not contained: nothing is ever written outside `dir`).
bool write_output_files(const std::string& dir, const std::vector<OutputFile>& files,
                        Diagnostics& diags);

}  // namespace efc
