// The runtime sources (efc_runtime.h/.cc, efc_mujoco.h/.cc) embedded in the
// compiler at build time (embed_runtime.cmake), so an output folder is
// self-contained: the generated code compiles against this exact copy.
#pragma once

#include <string>
#include <vector>

namespace efc {

struct EmbeddedFile {
  const char* path;  // relative to the output folder: "efc_runtime/efc_runtime.h", "efc_mujoco_runtime.h"
  const char* text;
};
const std::vector<EmbeddedFile>& embedded_runtime_files();
// The same runtime with its MuJoCo binding as one single-header library,
// "efc_mujoco_runtime.h" (amalgamate_runtime.cmake): what a MuJoCo output
// folder carries.
const std::vector<EmbeddedFile>& embedded_mujoco_runtime_files();

}  // namespace efc
