// The generated Bullet program: <name>_bullet.cc = the engine text
// (efc_bullet_engine.h, embedded at build time: the fixed part, compiled only
// in the output folder, where it includes efc_runtime/) + the object as tables
// + main(); and its CMakeLists.txt and README.md.
#pragma once

#include <string>

#include "backends/bullet/bullet_model.h"
#include "compiler/ir.h"

namespace efc {
namespace bullet {

std::string emit_program(const Object& obj, const Model& model);
std::string emit_cmake(const Object& obj);
std::string emit_readme(const Object& obj, const Model& model);

}  // namespace bullet
}  // namespace efc
