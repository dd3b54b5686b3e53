// What the DSL's lexer, parser and printer must agree on: which characters
// make words, and which words are keywords in which block. One definition, so
// the printer never writes a key the parser would read as a keyword.
#pragma once

#include <string>

namespace efc::dsl {

inline bool is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }

// The kind of block a statement stands in (grammar/efc.ebnf).
enum class Ctx { Object, Part, Function, Wrapper, Compound, Generic };

// True when `w` starts a keyword statement in a block of kind `ctx`.
inline bool is_keyword(Ctx ctx, const std::string& w) {
  const bool geometry = w == "box" || w == "cylinder" || w == "sphere" || w == "mesh" ||
                        w == "compound";
  switch (ctx) {
    case Ctx::Object: return w == "part" || w == "function";
    case Ctx::Part: return geometry || w == "joint" || w == "geometry";
    case Ctx::Function: return w == "mapping" || w == "effect";
    case Ctx::Wrapper: return geometry;
    case Ctx::Compound: return geometry || w == "geometry";
    case Ctx::Generic: return false;
  }
  return false;
}

}  // namespace efc::dsl
