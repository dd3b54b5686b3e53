// How a backend tells the user what it could not express: a W0900 warning
// located at the spec field it concerns (file, line, column, JSON pointer),
// never a silent drop and never an unlocated message.
#pragma once

#include <string>

#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc {

// The location of `pointer` in the spec: its own position, or the nearest
// enclosing field's when the value has none (a default filled by resolve()).
SourceLoc spec_location(const Object& obj, const std::string& pointer);

// Adds W0900 at `loc` (in obj.file).
void warn_target(Diagnostics& diags, const Object& obj, const SourceLoc& loc,
                 const std::string& message);

}  // namespace efc
