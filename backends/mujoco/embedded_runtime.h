// The runtime sources (efc_runtime.h/.cc, efc_mujoco.h/.cc) embedded in the
// compiler at build time (embed_runtime.cmake), so a MuJoCo output folder is
// self-contained: the generated callbacks compile against this exact copy.
#pragma once

#include <string>
#include <vector>

namespace efc {

struct EmbeddedFile {
  const char* path;  // relative to the output folder: "efc_runtime/efc_mujoco.h"
  const char* text;
};
const std::vector<EmbeddedFile>& embedded_runtime_files();

}  // namespace efc
