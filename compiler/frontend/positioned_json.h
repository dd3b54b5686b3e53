// Stage 1 of the JSON reader: text -> nlohmann::json DOM plus the line and
// column of every value and key, keyed by JSON pointer.
//
// nlohmann::json values carry no positions, so the parse goes through
// sax_parse with a handler that walks a cursor over the same text in step with
// the SAX events (each event is exactly one token), and builds the DOM itself.
// Nesting deeper than max_depth stops the parse with an error: the SAX parser
// is iterative and so is this handler, so 100000 '[' cannot overflow the stack.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include <nlohmann/json.hpp>

#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc::frontend {

using Positions = SourcePositions;

struct PositionedJson {
  nlohmann::json value;
  // Values under their JSON pointer; keys under key_position(pointer).
  Positions positions;
};

// Where a key's position is stored: "key:" + pointer (no pointer starts with
// "key:", pointers are "" or start with '/').
inline std::string key_position(const std::string& pointer) { return "key:" + pointer; }

// Offset of the first byte that is not well-formed UTF-8, or npos.
size_t first_invalid_utf8(std::string_view s);

// "/a" + "b/c" -> "/a/b~1c" (RFC 6901 escaping).
std::string pointer_append(const std::string& base, std::string_view token);

// What a value is, for messages: "an object", "an array", "a string", "a
// boolean", "null", "a number".
std::string json_kind_phrase(const nlohmann::json& v);

// Errors E0002 (empty), E0003 (syntax), E0004 (not UTF-8), E0005 (too deep),
// E0006 (number overflow), E0007 (duplicate key) go to diags. Returns nullopt
// when the text is not a usable JSON document (duplicate keys still return it,
// with the error reported).
std::optional<PositionedJson> parse_positioned(std::string_view text, const std::string& file,
                                               size_t max_depth, Diagnostics& diags);

}  // namespace efc::frontend
