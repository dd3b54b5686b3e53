// Backend::emit for Bullet: the model (bullet_model.cc), the program text
// (bullet_program.cc, bullet_engine.cc) and the copied runtime sources.
#include "backends/bullet/bullet_backend.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sys/stat.h>

#include "backends/backend.h"
#include "backends/bullet/bullet_model.h"
#include "backends/bullet/bullet_program.h"
#include "backends/bullet/embedded_profile.h"
#include "backends/mujoco/embedded_runtime.h"

namespace efc {

namespace {

bool put(const std::string& path, const std::string& text, Diagnostics& diags) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (out) return true;
  diags.error("E0900", path, 0, 0, "", "cannot write '" + path + "': " + std::strerror(errno));
  return false;
}

class BulletBackend : public Backend {
 public:
  const char* name() const override { return "bullet"; }
  const char* description() const override {
    return "Bullet 3 btMultiBody program (C++, CMake) over the efc runtime, same CSV as efc play";
  }
  bool emit(const Object& obj, const std::string& dir, Diagnostics& diags) const override {
    return write_bullet_target(obj, dir, diags);
  }
};

}  // namespace

bool write_bullet_target(const Object& obj, const std::string& dir, Diagnostics& diags) {
  const bullet::Model model = bullet::make_model(obj, 0.002);
  for (size_t i = 0; i < model.warnings.size(); ++i) {
    const std::string& ptr = model.warning_pointers[i];
    const auto at = obj.positions.find(ptr);
    const int line = at != obj.positions.end() ? at->second.first : 0;
    const int col = at != obj.positions.end() ? at->second.second : 0;
    diags.warning("W0900", obj.file, line, col, ptr, model.warnings[i]);
  }
  const std::string rt = dir + "/efc_runtime";
  if (::mkdir(rt.c_str(), 0777) != 0 && errno != EEXIST) {
    diags.error("E0900", rt, 0, 0, "", "cannot create '" + rt + "': " + std::strerror(errno));
    return false;
  }
  for (const EmbeddedFile& f : embedded_runtime_files()) {
    const std::string p = f.path;
    if (p != "efc_runtime/efc_runtime.h" && p != "efc_runtime/efc_runtime.cc") continue;
    if (!put(dir + "/" + p, f.text, diags)) return false;
  }
  for (const EmbeddedFile& f : embedded_profile_files())
    if (!put(dir + "/" + f.path, f.text, diags)) return false;
  return put(dir + "/" + obj.name + "_bullet.cc", bullet::emit_program(obj, model), diags) &&
         put(dir + "/CMakeLists.txt", bullet::emit_cmake(obj), diags) &&
         put(dir + "/README.md", bullet::emit_readme(obj, model), diags);
}

const Backend* bullet_backend() {
  static const BulletBackend backend;
  return &backend;
}

}  // namespace efc
