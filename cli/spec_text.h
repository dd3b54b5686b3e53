// What efc fmt and efc convert share: reading a spec document with the shape
// checks only (a spec still being written can be formatted), rendering it in
// either spelling, and replacing a file atomically.
#pragma once

#include <optional>
#include <string>

#include "cli/report.h"
#include "compiler/frontend/dsl.h"
#include "compiler/frontend/json_reader.h"

namespace efc {

bool is_json_path(const std::string& path);

// Reads `path` (either format), reporting every problem; nullopt with *rc set
// (2: unreadable, 1: wrong) on failure.
std::optional<SpecDocument> read_document_reported(Report& report, const std::string& path, int* rc);

// The document in canonical DSL (with its comments) or canonical JSON.
std::string render_document(const SpecDocument& doc, bool dsl);

// Writes `text` to `path` through a temporary file in the same folder and a
// rename, so a failure never leaves a half-written file.
bool write_atomically(const std::string& path, const std::string& text, std::string* error);

}  // namespace efc
