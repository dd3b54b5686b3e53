// The Bullet target (`--target bullet`): OUT/bullet/ holds <name>_bullet.cc
// (a standalone btMultiBody program over the efc runtime), efc_runtime/
// (runtime + receptor profiles, copied), CMakeLists.txt and README.md.
#pragma once

#include <string>

#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc {

// Writes the Bullet target into `dir` (existing, empty). Warnings (W0900)
// name what Bullet cannot represent. Returns false after adding an error.
bool write_bullet_target(const Object& obj, const std::string& dir, Diagnostics& diags);

}  // namespace efc
