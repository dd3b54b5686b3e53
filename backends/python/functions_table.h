// <name>_functions.json (format "efc-functions", version 1): the function
// templates, fully resolved and in evaluation order, with every name the
// Python scripts need to find in the URDF they load. The contract is
// backends/python/README.md; efc_templates.py reads it.
#pragma once

#include <string>

#include "backends/urdf/urdf_backend.h"
#include "compiler/ir.h"

namespace efc {

// The drive gains in it are chosen for this physics step (s).
constexpr double kPythonTimestep = 0.002;

std::string functions_table_json(const Object& obj, const urdf::Plan& plan);

}  // namespace efc
