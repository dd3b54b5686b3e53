#include "compiler/frontend/mesh_path.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

namespace efc::frontend {

namespace fs = std::filesystem;

// True when a `..` climbs above the folder the path starts in. Lexical only:
// symlinks inside the folder are the user's business.
static bool escapes(const fs::path& p) {
  int depth = 0;
  for (const auto& part : p) {
    const std::string s = part.string();
    if (s.empty() || s == ".") continue;
    if (s == "..") {
      if (--depth < 0) return true;
    } else {
      ++depth;
    }
  }
  return false;
}

MeshPathCheck check_mesh_path(const std::string& written, const std::string& base_dir,
                              bool allow_absolute) {
  MeshPathCheck r;
  fs::path p(written);
  if (written.empty()) {
    r.code = "E0114";
    r.message = "mesh path is empty";
    r.hint = "name an .obj, .stl or .ply file relative to the spec's folder";
    return r;
  }
  if (p.is_absolute() && !allow_absolute) {
    r.code = "E0113";
    r.message = "mesh path '" + written + "' is absolute";
    r.hint = "write it relative to the spec's folder (or pass --allow-absolute-paths)";
    return r;
  }
  if (!p.is_absolute() && escapes(p)) {
    r.code = "E0112";
    r.message = "mesh path '" + written + "' leaves the spec's folder";
    r.hint = "copy the mesh next to the spec (e.g. meshes/) and refer to it from there";
    return r;
  }
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".obj" && ext != ".stl" && ext != ".ply") {
    r.code = "E0114";
    r.message = "mesh '" + written + "' has an unsupported file type" +
                (ext.empty() ? std::string() : " (" + ext + ")");
    r.hint = "convert it to .obj, .stl or .ply";
    return r;
  }
  std::error_code ec;
  fs::path full = p.is_absolute() ? p : fs::path(base_dir.empty() ? "." : base_dir) / p;
  fs::path abs = fs::absolute(full, ec);
  if (ec) abs = full;
  r.resolved = abs.lexically_normal().string();
  if (!fs::is_regular_file(r.resolved, ec)) {
    r.code = "E0115";
    r.message = "mesh file '" + written + "' not found (looked for " + r.resolved + ")";
    r.hint = "check the spelling; relative paths start at the spec's folder";
  }
  return r;
}

}  // namespace efc::frontend
