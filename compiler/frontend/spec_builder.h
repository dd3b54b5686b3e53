// Stage 2 of the JSON reader: a positioned DOM -> the IR, checking the
// document's shape on the way (types, required and unknown keys, names, enum
// values, array lengths, colours, mesh paths). Every problem is reported;
// fields with a problem keep their IR defaults.
#pragma once

#include "compiler/diagnostics.h"
#include "compiler/frontend/json_reader.h"
#include "compiler/frontend/positioned_json.h"
#include "compiler/ir.h"

namespace efc::frontend {

// obj.file, obj.base_dir and obj.positions must be set already.
void build_object(const nlohmann::json& doc, Object& obj, const ReadOptions& opts,
                  Diagnostics& diags);

}  // namespace efc::frontend
