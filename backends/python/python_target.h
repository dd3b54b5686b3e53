// What the three Python targets (Genesis, Isaac Lab, OmniGibson) share: each
// writes OUT/<target>/ with the URDF and meshes it loads (the URDF backend's
// bytes), <name>_functions.json, efc_templates.py, the script
// <name>_<target>.py (a generated header, the target's fixed glue, a footer)
// and a README; and warns (W0900, located) for every effect or joint feature
// its simulator realises only approximately. What differs per target is data:
// the glue file and target.json (the simulator's version, installation, and
// how each effect is realised), both embedded at build time.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "backends/backend.h"
#include "backends/common/embedded.h"

namespace efc {

struct PythonTargetSpec {
  const char* name;         // "genesis": folder, --target, script suffix
  std::vector<std::string> aliases;
  const char* description;  // for --help
  const std::vector<EmbeddedFile>& (*glue)();   // efc_<target>.py
  const std::vector<EmbeddedFile>& (*facts)();  // target.json
};

class PythonTargetBackend : public Backend {
 public:
  explicit PythonTargetBackend(PythonTargetSpec spec);
  const char* name() const override { return spec_.name; }
  const char* description() const override { return spec_.description; }
  std::vector<std::string> aliases() const override { return spec_.aliases; }
  bool generate(const Object& obj, Diagnostics& diags, std::vector<OutputFile>* files) const override;

 private:
  PythonTargetSpec spec_;
  // target.json, parsed once. It is compiled in: a file that does not parse
  // is a build defect, which generate() reports (the conformance test shows it).
  nlohmann::json facts_;
};

}  // namespace efc
