// Files embedded in the compiler at build time (backends/common/embed_files.cmake,
// called through efc_embed() in backends/CMakeLists.txt): the fixed code output
// folders carry or are built from. Each set is compiled into the backend
// library that uses it, so no backend carries another's files.
#pragma once

#include <string>
#include <vector>

namespace efc {

struct EmbeddedFile {
  const char* path;  // in the output folder: "efc_runtime/efc_runtime.h", "efc_templates.py"
  const char* text;
};

// runtime/efc_runtime.{h,cc} and efc_profile.{h,cc} as efc_runtime/<file>:
// the Bullet target's copy of the runtime and the receptor profiles.
const std::vector<EmbeddedFile>& embedded_runtime_sources();
// efc_mujoco_runtime.h: the runtime and its MuJoCo binding as one
// single-header library (backends/mujoco/amalgamate_runtime.cmake).
const std::vector<EmbeddedFile>& embedded_mujoco_runtime();
// efc_bullet_engine.h: the fixed part of every generated Bullet program.
const std::vector<EmbeddedFile>& embedded_bullet_engine();

// efc_templates.py: the runtime every Python target carries.
const std::vector<EmbeddedFile>& embedded_python_runtime();
// Each Python target's fixed glue (efc_<target>.py) and its facts (target.json).
const std::vector<EmbeddedFile>& embedded_genesis_glue();
const std::vector<EmbeddedFile>& embedded_genesis_facts();
const std::vector<EmbeddedFile>& embedded_isaaclab_glue();
const std::vector<EmbeddedFile>& embedded_isaaclab_facts();
const std::vector<EmbeddedFile>& embedded_omnigibson_glue();
const std::vector<EmbeddedFile>& embedded_omnigibson_facts();

// The text of the one file in `set` (a set of one file, such as the engine).
inline std::string embedded_text(const std::vector<EmbeddedFile>& set) {
  return set.empty() ? std::string() : std::string(set.front().text);
}

}  // namespace efc
