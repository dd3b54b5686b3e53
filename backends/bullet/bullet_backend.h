// The Bullet target (`--target bullet`): OUT/bullet/ holds <name>_bullet.cc
// (a standalone btMultiBody program over the efc runtime), efc_runtime/
// (runtime + receptor profiles, copied), CMakeLists.txt and README.md.
#pragma once

#include <vector>

#include "backends/common/output_file.h"
#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc {

// The target folder in memory. Warnings (W0900) name what Bullet cannot
// represent. Returns false after adding an error.
bool generate_bullet_target(const Object& obj, Diagnostics& diags, std::vector<OutputFile>* files);

}  // namespace efc
