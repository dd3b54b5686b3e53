// The receptor profile sources (runtime/efc_profile.h/.cc) embedded in the
// compiler at build time by backends/mujoco/embed_runtime.cmake (run a second
// time with other files, see backends/CMakeLists.txt), so a Bullet output
// folder is self-contained. Paths: "efc_runtime/efc_profile.h", ".cc".
#pragma once

#include "backends/mujoco/embedded_runtime.h"

namespace efc {

const std::vector<EmbeddedFile>& embedded_profile_files();

}  // namespace efc
