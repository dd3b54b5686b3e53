// Helpers shared by the MuJoCo backend's files (not a public interface). The
// target-neutral rules (layout, gains, pools, effect points) are in
// backends/common/lowering.h, numbers and escaping in backends/common/text.h.
#pragma once

#include <string>
#include <vector>

#include "backends/common/output_file.h"
#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc {
struct MjcfOptions;
namespace mjcf {
struct Plan;
}  // namespace mjcf

// The generated <name>_callbacks.h (the C API of <name>_callbacks.cc).
std::string callbacks_header(const Object& obj);

// The model's files (meshes, then <name>.xml) from an existing plan, so a
// caller that also needs the plan (the README) makes it once.
bool generate_model_files(const Object& obj, const MjcfOptions& options, mjcf::Plan* plan,
                          Diagnostics& diags, std::vector<OutputFile>* files);

}  // namespace efc
