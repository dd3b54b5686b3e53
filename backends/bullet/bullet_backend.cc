// Backend::generate for Bullet: the model (bullet_model.cc), the program text
// (bullet_program.cc around the embedded efc_bullet_engine.h) and the copied
// runtime sources.
#include "backends/bullet/bullet_backend.h"

#include "backends/backend.h"
#include "backends/bullet/bullet_model.h"
#include "backends/bullet/bullet_program.h"
#include "backends/common/embedded.h"
#include "backends/common/naming.h"
#include "backends/common/report.h"

namespace efc {

namespace {

class BulletBackend : public Backend {
 public:
  const char* name() const override { return "bullet"; }
  const char* description() const override {
    return "Bullet 3 btMultiBody program (C++, CMake) over the efc runtime, same CSV as efc play";
  }
  bool generate(const Object& obj, Diagnostics& diags, std::vector<OutputFile>* files) const override {
    return generate_bullet_target(obj, diags, files);
  }
};

}  // namespace

bool generate_bullet_target(const Object& obj, Diagnostics& diags, std::vector<OutputFile>* files) {
  const bullet::Model model = bullet::make_model(obj, 0.002);
  for (size_t i = 0; i < model.warnings.size(); ++i)
    warn_target(diags, obj, spec_location(obj, model.warning_pointers[i]), model.warnings[i]);
  for (const EmbeddedFile& f : embedded_runtime_sources()) files->push_back({f.path, f.text});
  files->push_back({naming::bullet_program(obj) + ".cc", bullet::emit_program(obj, model)});
  files->push_back({"CMakeLists.txt", bullet::emit_cmake(obj)});
  files->push_back({"README.md", bullet::emit_readme(obj, model)});
  return true;
}

const Backend* bullet_backend() {
  static const BulletBackend backend;
  return &backend;
}

}  // namespace efc
