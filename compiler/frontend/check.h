// The type rules of spec v1 that span fields: references, the part tree, the
// function graph, value ranges. Every violation is reported (not just the first)
// with the line and column of the offending field.
#pragma once

#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc {

// Before defaults are filled: references (parents, receptor, effector), the
// root, the part tree, the function graph (no cycles, no duplicate
// (effector, effect type) writers), joint and effect ranges, physical values,
// non-zero delta and gain. Fills parent_index, receptor_index, effector_index.
void check_structure(Object& obj, Diagnostics& diags);

// After resolve() filled defaults: thresholds inside the receptor range,
// a geometry effect's range inside its effector joint's range, and the rest
// that needs resolved values.
void check_resolved(const Object& obj, Diagnostics& diags);

// Line and column for a JSON pointer: the value's own position, else the
// nearest enclosing value's, else 0:0.
SourceLoc locate(const Object& obj, const std::string& pointer);

// Adds an error located at `pointer`.
void report(Diagnostics& diags, const Object& obj, const char* code, const std::string& pointer,
            std::string message, std::string hint = {});
void report_warning(Diagnostics& diags, const Object& obj, const char* code,
                    const std::string& pointer, std::string message, std::string hint = {});

}  // namespace efc

namespace efc {

// Appends `from` to `to` sorted by line and column (stable), so a run's
// messages read top to bottom through the file.
void append_in_file_order(const Diagnostics& from, Diagnostics& to);

}  // namespace efc
