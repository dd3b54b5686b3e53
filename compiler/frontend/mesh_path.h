// The rules for mesh file paths in a spec: relative to the spec's folder and
// never leaving it (a spec from elsewhere must not read arbitrary files), no
// absolute paths unless allowed, a mesh extension the geometry stage can load.
#pragma once

#include <string>

namespace efc::frontend {

struct MeshPathCheck {
  std::string resolved;     // absolute, normalised; set when code is empty
  const char* code = "";    // "" = fine, else E0112..E0115
  std::string message, hint;
};

MeshPathCheck check_mesh_path(const std::string& written, const std::string& base_dir,
                              bool allow_absolute);

}  // namespace efc::frontend
