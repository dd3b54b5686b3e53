// The DSL front-end (.efc files, grammar/efc.ebnf): a second spelling of the
// spec v1 JSON document. The parser turns .efc text into the same positioned
// JSON document the JSON reader builds (positions point into the .efc file),
// so spec_builder and the checks run unchanged on it; the printer turns any
// spec document back into canonical .efc text. parse(print(doc)) == doc for
// every document the JSON reader accepts (values exactly, key order aside).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "compiler/diagnostics.h"
#include "compiler/frontend/dsl_comments.h"
#include "compiler/frontend/positioned_json.h"

namespace efc::dsl {

// .efc text -> positioned document. Every syntax error is reported in one run
// (the parser recovers at the next statement), each with file:line:col, the
// source line and a caret (Diagnostic::source_line). Unit errors (E0131: a
// unit that does not fit its field) are reported too. Returns nullopt when
// any error was found.
std::optional<frontend::PositionedJson> parse(std::string_view text, const std::string& file,
                                              size_t max_depth, Diagnostics& diags);

// parse(), also returning the file's comments attached to their statements.
std::optional<frontend::PositionedJson> parse_with_comments(std::string_view text,
                                                            const std::string& file,
                                                            size_t max_depth, Diagnostics& diags,
                                                            CommentMap* comments);

// A spec document -> canonical .efc text (what `efc fmt` writes), with the
// comments put back where they were when `comments` is given.
std::string print(const nlohmann::json& doc, const CommentMap* comments = nullptr);

// A spec document -> canonical JSON text (what `efc convert x.efc -o y.json`
// writes): spec key order, short arrays on one line, integers without ".0".
std::string print_json(const nlohmann::json& doc);

}  // namespace efc::dsl
