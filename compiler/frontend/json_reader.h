// The JSON front-end: reads a spec v1 document into the IR, recording the line
// and column of every value (nlohmann::json::sax_parse through a counting
// input adapter) so every diagnostic points into the file the user wrote.
//
// It checks the document's shape: syntax, types, required and unknown keys
// (`x-` keys are kept), names, enum values, finite numbers, and that file
// paths stay inside the spec's folder. Cross-references and value rules are
// check.h's job.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "compiler/diagnostics.h"
#include "compiler/frontend/dsl_comments.h"
#include "compiler/ir.h"

namespace efc {

struct ReadOptions {
  bool allow_absolute_paths = false;
  size_t max_depth = 256;  // deeper nesting is an error, never a stack overflow
};

// Returns the object when the document has the right shape (it may still have
// errors for check() to find); nullopt when it cannot be used. Errors go to diags.
// Any reader error (syntax or shape, codes E00xx/E01xx) gives nullopt, so the
// checks never see a half-filled IR; all of the reader's errors are reported,
// in file order. Object::positions holds every value's line:col under its JSON
// pointer, and every key's under "key:" + pointer (frontend/positioned_json.h).
std::optional<Object> read_json_text(std::string_view text, const std::string& file,
                                     const std::string& base_dir, const ReadOptions& opts,
                                     Diagnostics& diags);

// Reads a file. Sets *io_error (exit code 2) when the file cannot be read.
std::optional<Object> read_json_file(const std::string& path, const ReadOptions& opts,
                                     Diagnostics& diags, bool* io_error);

// ---- Either format, chosen by the file's extension: `.efc` is the DSL
// (grammar/efc.ebnf, compiler/frontend/dsl.h), anything else JSON.
bool is_dsl_path(const std::string& path);

// read_json_text for JSON, the DSL parser + the same shape checks for .efc.
// For .efc files every diagnostic in `file` carries its source line.
std::optional<Object> read_spec_text(std::string_view text, const std::string& file,
                                     const std::string& base_dir, const ReadOptions& opts,
                                     Diagnostics& diags);

// Reads a file of either format. Sets *io_error (exit code 2) when the file
// cannot be read; *text (when given) receives its contents.
std::optional<Object> read_spec_file(const std::string& path, const ReadOptions& opts,
                                     Diagnostics& diags, bool* io_error,
                                     std::string* text = nullptr);

// A spec file's document itself (after the shape checks, before the cross-
// field rules), for tools that rewrite it (efc fmt, efc convert).
struct SpecDocument {
  nlohmann::json value;
  dsl::CommentMap comments;  // .efc files only
  std::string text;          // the file as read
};
std::optional<SpecDocument> read_spec_document(const std::string& path, const ReadOptions& opts,
                                               Diagnostics& diags, bool* io_error);

// The whole file as text, or nullopt with error E0001 (exit code 2).
std::optional<std::string> read_text_file(const std::string& path, Diagnostics& diags);

// True when `name` matches ^[A-Za-z_][A-Za-z0-9_]{0,63}$ (names reach XML, C++, Python).
bool is_valid_name(std::string_view name);

}  // namespace efc
