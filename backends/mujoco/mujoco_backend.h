// The MuJoCo target: MJCF with mesh assets, plus <name>_callbacks.cc (a
// generated mjcb_control over the efc runtime) and a README, self-contained
// (the runtime is copied next to them as one header).
#pragma once

#include <string>
#include <vector>

#include "backends/common/output_file.h"
#include "compiler/diagnostics.h"
#include "compiler/ir.h"
#include "runtime/mujoco/efc_mujoco.h"

namespace efc {

struct MjcfOptions {
  // Add a stiff position actuator efc_drive_<part> on every receptor that no
  // function drives (the playback harness moves receptors through them).
  bool drive_receptors = false;
  // Folder of mesh assets, relative to the XML file.
  std::string mesh_dir = "meshes";
  double timestep = 0.002;
};

// The function table in evaluation order (topological over chains): the rows
// the harness hands to efc_mj::Controller and the generated callbacks embed.
std::vector<efc_mj::FunctionBinding> build_bindings(const Object& obj);

// The MJCF document (mesh files referenced under options.mesh_dir).
std::string emit_mjcf(const Object& obj, const MjcfOptions& options);

// <name>.xml and its mesh files, in memory (plan warnings go to diags).
// False after adding an error (a mesh that was never loaded).
bool generate_mujoco_model(const Object& obj, const MjcfOptions& options, Diagnostics& diags,
                           std::vector<OutputFile>* files);

// The whole `--target mujoco` folder in memory: the model, the callbacks
// (.cc/.h), efc_mujoco_runtime.h, CMakeLists.txt and README.md; what
// `efc compile` writes. Everything efc computes, nothing the file system does.
bool generate_mujoco_target(const Object& obj, Diagnostics& diags, std::vector<OutputFile>* files);

// Writes <dir>/<name>.xml and its meshes (no callbacks): what `efc play` loads.
// Returns false after adding an error (e.g. an unwritable folder).
bool write_mujoco_model(const Object& obj, const std::string& dir, const MjcfOptions& options,
                        Diagnostics& diags, std::string* xml_path);

// The generated <name>_callbacks.cc source.
std::string emit_callbacks(const Object& obj);

}  // namespace efc
