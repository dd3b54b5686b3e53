// The DSL parser: tokens -> the positioned spec document (dsl.h).
//
// Recursive descent over grammar/efc.ebnf. A statement ends at a line break,
// a ';' or its block's '}'; after an error the parser skips to the next
// statement boundary at the same nesting level and goes on, so one run
// reports every syntax error. Units are checked and converted after the whole
// document is built, because a field's dimension can depend on a part that
// is declared later (a mapping threshold is in its receptor joint's unit).
#include <cmath>
#include <cstdlib>

#include "compiler/frontend/dsl.h"
#include "compiler/frontend/dsl_comments.h"
#include "compiler/frontend/dsl_lexer.h"
#include "compiler/frontend/dsl_syntax.h"
#include "compiler/frontend/dsl_units.h"

namespace efc::dsl {
namespace {

using nlohmann::json;
using frontend::key_position;
using frontend::pointer_append;

// A number in the document: integral values become JSON integers, so JSON
// written from a .efc file says 20, not 20.0 (nlohmann compares 20 == 20.0).
json number_json(double v) {
  if (std::isfinite(v) && v == std::floor(v) && std::fabs(v) <= 9007199254740992.0 &&
      !(v == 0 && std::signbit(v)))
    return json(static_cast<std::int64_t>(v));
  return json(v);
}

// An integer literal (no '.', no exponent) that fits 64 bits, as an exact JSON
// integer: a double cannot hold 2^53 + 1. nullopt for anything else.
std::optional<json> integer_literal(const Token& t) {
  if (t.text.find_first_of(".eE") != std::string::npos) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  if (t.text[0] == '-') {
    long long i = std::strtoll(t.text.c_str(), &end, 10);
    // "-0" is left to the double path, which keeps its sign.
    if (errno == 0 && *end == '\0' && i != 0) return json(static_cast<std::int64_t>(i));
    return std::nullopt;
  }
  unsigned long long u = std::strtoull(t.text.c_str(), &end, 10);
  if (errno != 0 || *end != '\0') return std::nullopt;
  if (u <= 9223372036854775807ULL) return json(static_cast<std::int64_t>(u));
  return json(static_cast<std::uint64_t>(u));
}

// A number token of a statement as JSON: exact integers stay exact, anything
// else is number_json(v).
json literal_json(const Token& t, double v) {
  if (auto i = integer_literal(t)) return *i;
  return number_json(v);
}

struct UnitUse {
  std::vector<std::string> path;  // of the number, or of the array for ranges and vectors
  std::string pointer;
  std::vector<double> raw;        // as written, before conversion
  std::vector<bool> has_unit;     // per number: written with the unit (else bare)
  std::string unit;
  int line = 0, col = 0;          // the unit token
};

struct Fatal {};  // nesting too deep or too many errors: stop parsing

class Parser {
 public:
  Parser(std::string_view text, const std::string& file, size_t max_depth, Diagnostics& diags)
      : text_(text), file_(file), max_depth_(max_depth), diags_(diags) {
    toks_ = tokenize(text, &comments_list_);
  }

  std::optional<frontend::PositionedJson> run(CommentMap* comments) {
    out_.value = json::object();
    try {
      parse_file();
    } catch (const Fatal&) {
      return std::nullopt;
    }
    apply_units();
    if (comments) *comments = attach_comments(comments_list_, statements_);
    if (errors_ > 0) return std::nullopt;
    return std::move(out_);
  }

 private:
  // ------------------------------------------------------------ tokens
  const Token& cur() const { return toks_[i_]; }
  const Token& peek(size_t k = 1) const { return toks_[std::min(i_ + k, toks_.size() - 1)]; }
  bool at(Tok k) const { return cur().kind == k; }
  bool at_word(const char* w) const { return cur().kind == Tok::Ident && cur().text == w; }
  const Token& take() {
    const Token& t = toks_[i_];
    if (i_ + 1 < toks_.size()) ++i_;
    return t;
  }

  void error_at(const char* code, int line, int col, const std::string& pointer,
                std::string message, std::string hint = {}) {
    Diagnostic d;
    d.code = code;
    d.file = file_;
    d.line = line;
    d.col = col;
    d.pointer = pointer;
    d.message = std::move(message);
    d.hint = std::move(hint);
    diags_.add(std::move(d));
    if (++errors_ >= kMaxErrors) {
      diags_.error("E0010", file_, line, col, "", "too many errors; stopping here");
      throw Fatal{};
    }
  }
  void error(const Token& t, std::string message, std::string hint = {}) {
    if (t.kind == Tok::Error) {
      error_at("E0011", t.line, t.col, "", t.text);
      return;
    }
    error_at("E0010", t.line, t.col, "", std::move(message), std::move(hint));
  }

  // Skips to the next statement boundary at this nesting level: a line
  // break, a ';' (consumed) or the enclosing '}' (left for the block).
  void sync() {
    int depth = 0;
    bool moved = false;
    for (;;) {
      const Token& t = cur();
      if (t.kind == Tok::End) return;
      if (depth == 0 && t.kind == Tok::RBrace) return;
      if (depth == 0 && moved && t.first_on_line) return;
      take();
      moved = true;
      if (t.kind == Tok::LBrace || t.kind == Tok::LParen || t.kind == Tok::LBracket) ++depth;
      if (t.kind == Tok::RParen || t.kind == Tok::RBracket || t.kind == Tok::RBrace) {
        if (depth > 0) --depth;
      }
      if (depth == 0 && t.kind == Tok::Semicolon) return;
    }
  }

  // After a complete statement: a line break, ';', '}' or the end must follow.
  bool end_statement(const std::string& what) {
    const Token& t = cur();
    if (t.kind == Tok::Semicolon) {
      take();
      return true;
    }
    if (t.kind == Tok::RBrace || t.kind == Tok::End || t.first_on_line) return true;
    error(t, "expected a line break or ';' after " + what + ", found " + describe(t),
          "write one statement per line, or separate them with ';'");
    sync();
    return false;
  }

  void enter(const Token& t) {
    if (++depth_ > max_depth_) {
      error_at("E0005", t.line, t.col, "",
               "nesting deeper than " + std::to_string(max_depth_) + " levels",
               "a spec needs fewer than ten; is this file generated by mistake?");
      throw Fatal{};
    }
  }
  void leave() { --depth_; }

  void set_pos(const std::string& pointer, const Token& t) {
    out_.positions[pointer] = {t.line, t.col};
  }
  void set_key_pos(const std::string& pointer, const Token& t) {
    out_.positions[key_position(pointer)] = {t.line, t.col};
  }
  void note_statement(const std::string& pointer, const Token& first) {
    statements_.push_back({pointer, first.line, first.col, first.offset});
  }

  // A value written in a statement's header (a part's name, a joint's type):
  // the key and the value are both located at its token.
  void header_field(json& node, const std::string& pointer, const char* key, const Token& t) {
    node[key] = t.text;
    set_pos(pointer + "/" + key, t);
    set_key_pos(pointer + "/" + key, t);
  }

  // The "parts" or "functions" list of the object, created at its first
  // element; nullptr (reported) when the key holds something else already.
  json* list_for(json& root, const std::string& pointer, const char* key, const Token& kw) {
    const std::string p = pointer_append(pointer, key);
    if (!root.contains(key)) {
      root[key] = json::array();
      set_key_pos(p, kw);
      set_pos(p, kw);
    } else if (!root[key].is_array()) {
      error_at("E0007", kw.line, kw.col, p, std::string("duplicate key '") + key + "'",
               "keep one of them");
      return nullptr;
    }
    return &root[key];
  }

  // Adds `key` to `target` unless it is there already (E0007).
  bool claim(json& target, const std::string& pointer, const std::string& key, const Token& at) {
    const std::string p = pointer_append(pointer, key);
    if (target.contains(key)) {
      auto it = out_.positions.find(key_position(p));
      std::string first = it == out_.positions.end()
                              ? std::string()
                              : " (first at line " + std::to_string(it->second.first) + ")";
      error_at("E0007", at.line, at.col, p, "duplicate key '" + key + "'" + first,
               "keep one of them");
      return false;
    }
    set_key_pos(p, at);
    return true;
  }

  static std::vector<std::string> path_of(const std::string& pointer) {
    std::vector<std::string> out;
    size_t i = 0;
    while (i < pointer.size()) {
      size_t j = pointer.find('/', i + 1);
      std::string tok = pointer.substr(i + 1, j == std::string::npos ? std::string::npos : j - i - 1);
      std::string dec;
      for (size_t k = 0; k < tok.size(); ++k) {
        if (tok[k] == '~' && k + 1 < tok.size()) {
          dec += tok[k + 1] == '1' ? '/' : '~';
          ++k;
        } else {
          dec += tok[k];
        }
      }
      out.push_back(dec);
      if (j == std::string::npos) break;
      i = j;
    }
    return out;
  }

  // ------------------------------------------------------------ file
  void parse_file() {
    bool have_object = false;
    const Token& first = cur();
    set_pos("", first);
    if (first.kind == Tok::End) {
      error_at("E0002", 1, 1, "", "the file is empty",
               "a .efc file holds `efc 1` and `object NAME { ... }`");
      return;
    }
    while (!at(Tok::End)) {
      const Token& t = cur();
      if (t.kind == Tok::Semicolon) {
        take();
      } else if (at_word("efc")) {
        note_statement("/efc", t);
        take();
        if (!claim(out_.value, "", "efc", t)) {
          sync();
          continue;
        }
        if (!parse_value_into(out_.value, "", "efc", t, Ctx::Generic)) {
          sync();
          continue;
        }
        end_statement("the version");
      } else if (at_word("object")) {
        note_statement("", t);
        take();
        if (have_object) error(t, "a file holds one object; this is a second one");
        have_object = true;
        if (at(Tok::Ident)) {
          const Token& name = take();
          if (claim(out_.value, "", "name", name)) {
            out_.value["name"] = name.text;
            set_pos("/name", name);
          }
        }
        if (!at(Tok::LBrace)) {
          error(cur(), "expected '{' to open the object's block, found " + describe(cur()));
          sync();
          continue;
        }
        parse_block(Ctx::Object, out_.value, "");
        end_statement("the object");
      } else {
        error(t, "expected `efc 1` or `object NAME { ... }` at the top level, found " + describe(t),
              "parts, functions and other fields go inside the object's block");
        sync();
        if (at(Tok::RBrace)) take();  // a stray '}' at the top level
      }
    }
  }

  // '{' statements '}' into `target` (an object; for Compound, an array).
  void parse_block(Ctx ctx, json& target, const std::string& pointer) {
    const Token& open = take();  // '{'
    enter(open);
    for (;;) {
      const Token& t = cur();
      if (t.kind == Tok::RBrace) {
        take();
        break;
      }
      // `part NAME` or `function NAME` starting a line inside a part or a
      // deeper block: a '}' is missing above. Close the open blocks up to the
      // object's, so one missing brace does not swallow the rest of the file.
      if (ctx != Ctx::Object && t.kind == Tok::Ident && t.first_on_line &&
          (t.text == "part" || t.text == "function") && peek().kind == Tok::Ident &&
          !peek().first_on_line) {
        if (!unwinding_)
          error(t, "expected '}' to close the block opened at line " + std::to_string(open.line) +
                       ", column " + std::to_string(open.col) + " before this " + t.text);
        unwinding_ = true;
        break;
      }
      if (ctx == Ctx::Object) unwinding_ = false;
      if (t.kind == Tok::End) {
        error(t, "expected '}' to close the block opened at line " + std::to_string(open.line) +
                     ", column " + std::to_string(open.col));
        break;
      }
      if (t.kind == Tok::Semicolon) {
        take();
        continue;
      }
      parse_statement(ctx, target, pointer);
    }
    leave();
  }

  // A key: identifier, x- extension or quoted string. Quoted keys are never keywords.
  bool is_key_token(const Token& t) const {
    return t.kind == Tok::Ident || t.kind == Tok::Extension || t.kind == Tok::String;
  }

  void parse_statement(Ctx ctx, json& target, const std::string& pointer) {
    const Token& t = cur();
    if (t.kind == Tok::Ident && is_keyword(ctx, t.text)) {
      if (ctx == Ctx::Object) return t.text == "part" ? parse_part(target, pointer)
                                                       : parse_function(target, pointer);
      if (ctx == Ctx::Part && t.text == "joint") return parse_headed(target, pointer, "joint");
      if (ctx == Ctx::Function) return parse_headed(target, pointer, t.text);
      if (ctx == Ctx::Compound) return parse_compound_element(target, pointer);
      // Part or Wrapper: a geometry statement. In a part it fills the part's
      // "geometry" object; in a wrapper, the wrapper itself.
      if (ctx == Ctx::Part) {
        const std::string gp = pointer_append(pointer, "geometry");
        if (!target.contains("geometry")) {
          target["geometry"] = json::object();
          set_key_pos(gp, t);
          set_pos(gp, t);
        } else if (!target["geometry"].is_object()) {
          error_at("E0007", t.line, t.col, gp, "duplicate key 'geometry'", "keep one of them");
          take();
          sync();
          return;
        }
        if (t.text == "geometry") {
          note_statement(gp, t);
          take();
          if (!at(Tok::LBrace)) {
            error(cur(), "expected '{' after 'geometry', found " + describe(cur()));
            sync();
            return;
          }
          parse_block(Ctx::Wrapper, target["geometry"], gp);
          end_statement("the geometry block");
          return;
        }
        return parse_geometry_statement(target["geometry"], gp);
      }
      return parse_geometry_statement(target, pointer);
    }
    if (ctx == Ctx::Compound) {
      error(t, "expected a geometry (box, cylinder, sphere, mesh, compound or geometry) in a "
               "compound, found " + describe(t));
      sync();
      return;
    }
    if (!is_key_token(t)) {
      error(t, "expected a field name, found " + describe(t));
      sync();
      return;
    }
    // key value | key block
    take();
    const std::string key = t.text;
    const std::string p = pointer_append(pointer, key);
    note_statement(p, t);
    if (!claim(target, pointer, key, t)) {
      sync();
      return;
    }
    const bool extension = key.rfind("x-", 0) == 0;
    bool ok;
    if (extension) {
      const Token& v = cur();
      json value;
      ok = parse_json(value, p);
      if (ok) {
        target[key] = std::move(value);
        set_pos(p, v);
      }
    } else {
      ok = parse_value_into(target, pointer, key, t, Ctx::Generic);
    }
    if (!ok) {
      target.erase(key);
      sync();
      return;
    }
    end_statement("'" + key + "'");
  }

  // part NAME [: ROLE] { ... }
  void parse_part(json& root, const std::string& pointer) {
    const Token& kw = take();
    json* list = list_for(root, pointer, "parts", kw);
    if (!list) {
      sync();
      return;
    }
    json& parts = *list;
    const std::string p = pointer_append(pointer_append(pointer, "parts"), std::to_string(parts.size()));
    json part = json::object();
    note_statement(p, kw);
    set_pos(p, kw);
    if (at(Tok::Ident)) {
      const Token& name = take();
      header_field(part, p, "name", name);
      if (at(Tok::Colon)) {
        take();
        if (!at(Tok::Ident)) {
          error(cur(), "expected the part's role (base, receptor, effector, other) after ':', found " +
                           describe(cur()));
          sync();
          return;
        }
        const Token& role = take();
        header_field(part, p, "role", role);
      }
    }
    if (!at(Tok::LBrace)) {
      error(cur(), "expected '{' to open the part's block, found " + describe(cur()),
            "part NAME: ROLE { geometry, mass, joint ... }");
      sync();
      return;
    }
    parts.push_back(json::object());
    parse_block(Ctx::Part, part, p);
    // The block may have added "name"/"role" too: claim() reported those.
    parts.back() = std::move(part);
    end_statement("the part");
  }

  // function NAME [: RECEPTOR -> EFFECTOR] { ... }
  void parse_function(json& root, const std::string& pointer) {
    const Token& kw = take();
    json* list = list_for(root, pointer, "functions", kw);
    if (!list) {
      sync();
      return;
    }
    json& functions = *list;
    const std::string p =
        pointer_append(pointer_append(pointer, "functions"), std::to_string(functions.size()));
    json fn = json::object();
    note_statement(p, kw);
    set_pos(p, kw);
    if (at(Tok::Ident)) {
      const Token& name = take();
      header_field(fn, p, "name", name);
      if (at(Tok::Colon)) {
        take();
        if (!at(Tok::Ident) || peek().kind != Tok::Arrow || peek(2).kind != Tok::Ident) {
          error(cur(), "expected RECEPTOR -> EFFECTOR after ':', found " + describe(cur()),
                "function water: handle -> spout { ... }");
          sync();
          return;
        }
        const Token& r = take();
        take();  // ->
        const Token& e = take();
        header_field(fn, p, "receptor", r);
        header_field(fn, p, "effector", e);
      }
    }
    if (!at(Tok::LBrace)) {
      error(cur(), "expected '{' to open the function's block, found " + describe(cur()),
            "function NAME: RECEPTOR -> EFFECTOR { mapping ...; effect ... }");
      sync();
      return;
    }
    functions.push_back(json::object());
    parse_block(Ctx::Function, fn, p);
    functions.back() = std::move(fn);
    end_statement("the function");
  }

  // joint [TYPE] [on PARENT] [{ ... }]   mapping [TYPE] [{ ... }]   effect [TYPE] [{ ... }]
  void parse_headed(json& target, const std::string& pointer, const std::string& key) {
    const Token& kw = take();
    const std::string p = pointer_append(pointer, key);
    note_statement(p, kw);
    if (!claim(target, pointer, key, kw)) {
      sync();
      return;
    }
    json node = json::object();
    set_pos(p, kw);
    const bool joint = key == "joint";
    if (at(Tok::Ident) && !cur().first_on_line && !(joint && cur().text == "on")) {
      const Token& type = take();
      header_field(node, p, "type", type);
    }
    if (joint && at_word("on") && !cur().first_on_line) {
      take();
      if (!at(Tok::Ident)) {
        error(cur(), "expected the parent part's name after 'on', found " + describe(cur()));
        sync();
        return;
      }
      const Token& parent = take();
      header_field(node, p, "parent", parent);
    }
    if (at(Tok::LBrace)) parse_block(Ctx::Generic, node, p);
    target[key] = std::move(node);
    (void)kw;
    end_statement("the " + key);
  }

  // box { } | cylinder { } | sphere { } | mesh "path" [{ }] | compound { }
  // into the geometry object `wrapper` at `pointer`.
  void parse_geometry_statement(json& wrapper, const std::string& pointer) {
    const Token& kw = take();
    const std::string kind = kw.text;
    const std::string p = pointer_append(pointer, kind);
    note_statement(p, kw);
    if (!claim(wrapper, pointer, kind, kw)) {
      sync();
      return;
    }
    if (kind == "mesh") {
      if (!at(Tok::String)) {
        error(cur(), "expected the mesh file's path as a string after 'mesh', found " +
                         describe(cur()),
              "mesh \"meshes/handle.obj\" { scale (1, 1, 1) }");
        sync();
        return;
      }
      const Token& path = take();
      wrapper["mesh"] = path.text;
      set_pos(p, path);
      if (at(Tok::LBrace)) parse_block(Ctx::Wrapper, wrapper, pointer);
      end_statement("the mesh");
      return;
    }
    if (!at(Tok::LBrace)) {
      error(cur(), "expected '{' after '" + kind + "', found " + describe(cur()),
            kind == "compound" ? "compound { box { ... }; sphere { ... } }"
                               : kind + " { ... }");
      sync();
      return;
    }
    set_pos(p, cur());
    if (kind == "compound") {
      json elements = json::array();
      parse_block(Ctx::Compound, elements, p);
      wrapper["compound"] = std::move(elements);
    } else {
      json fields = json::object();
      parse_block(Ctx::Generic, fields, p);
      wrapper[kind] = std::move(fields);
    }
    end_statement("the " + kind);
  }

  // One element of a compound: a geometry statement into a new wrapper.
  void parse_compound_element(json& elements, const std::string& pointer) {
    const Token& kw = cur();
    const std::string p = pointer_append(pointer, std::to_string(elements.size()));
    json element = json::object();
    set_pos(p, kw);
    if (kw.text == "geometry") {
      note_statement(p, kw);
      take();
      if (!at(Tok::LBrace)) {
        error(cur(), "expected '{' after 'geometry', found " + describe(cur()));
        sync();
        return;
      }
      elements.push_back(json::object());
      parse_block(Ctx::Wrapper, element, p);
      end_statement("the geometry");
    } else {
      elements.push_back(json::object());
      parse_geometry_statement(element, p);
    }
    elements.back() = std::move(element);
  }

  // ------------------------------------------------------------ values
  // Parses the value of `key` (already claimed) into target[key].
  bool parse_value_into(json& target, const std::string& pointer, const std::string& key,
                        const Token& key_tok, Ctx) {
    const std::string p = pointer_append(pointer, key);
    const Token& t = cur();
    if (t.kind == Tok::LBrace) {
      json block = json::object();
      set_pos(p, t);
      parse_block(Ctx::Generic, block, p);
      target[key] = std::move(block);
      return true;
    }
    if (t.kind == Tok::LBracket) {
      json value;
      if (!parse_json(value, p)) return false;
      set_pos(p, t);
      target[key] = std::move(value);
      return true;
    }
    if (t.kind == Tok::String) {
      take();
      set_pos(p, t);
      target[key] = t.text;
      return true;
    }
    if (t.kind == Tok::Ident && !t.first_on_line) {
      take();
      set_pos(p, t);
      if (t.text == "true" || t.text == "false")
        target[key] = t.text == "true";
      else if (t.text == "null")
        target[key] = nullptr;
      else
        target[key] = t.text;
      return true;
    }
    if (t.kind == Tok::LParen) return parse_vector(target, p, key);
    if (t.kind == Tok::Number && !t.first_on_line) return parse_quantity_or_range(target, p, key);
    if (t.kind == Tok::Error) {
      error(t, "");
      return false;
    }
    error(t, "expected a value for '" + key_tok.text + "', found " + describe(t),
          "a number with an optional unit, lo .. hi, (x, y, z), a string, a word, or { ... }");
    return false;
  }

  bool read_number(const Token& t, double* v) {
    errno = 0;
    *v = std::strtod(t.text.c_str(), nullptr);
    if (!std::isfinite(*v)) {
      error_at("E0006", t.line, t.col, "", "number " + t.text + " is out of range",
               "write a finite number; SI values in a spec are far below 1e308");
      return false;
    }
    return true;
  }

  // An optional unit right after a number (same line): returns false on an
  // unknown unit (reported). *unit is empty when there is none.
  bool read_unit(std::string* unit, const Token** unit_tok) {
    unit->clear();
    const Token& t = cur();
    if (t.kind != Tok::Ident || t.first_on_line) return true;
    *unit_tok = &t;
    std::string name = t.text;
    // L/min and m/s are three tokens written together.
    if ((name == "L" || name == "m") && peek().kind == Tok::Slash && peek().offset == t.end &&
        peek(2).kind == Tok::Ident && peek(2).offset == peek().end) {
      std::string joined = name + "/" + peek(2).text;
      if (find_unit(joined)) {
        take();
        take();
        take();
        *unit = joined;
        return true;
      }
    }
    take();
    if (!find_unit(name)) {
      error_at("E0012", t.line, t.col, "", "unknown unit '" + name + "'",
               "units: " + unit_list() + " (a bare number is in the field's SI unit)");
      return false;
    }
    *unit = name;
    return true;
  }

  // number [unit] [.. number [unit]]
  bool parse_quantity_or_range(json& target, const std::string& p, const std::string& key) {
    const Token& first = take();
    double a = 0;
    if (!read_number(first, &a)) return false;
    std::string ua;
    const Token* ua_tok = nullptr;
    if (!read_unit(&ua, &ua_tok)) return false;
    set_pos(p, first);
    if (!at(Tok::DotDot)) {
      if (!ua.empty()) units_.push_back({path_of(p), p, {a}, {true}, ua, ua_tok->line, ua_tok->col});
      target[key] = literal_json(first, a);
      return true;
    }
    take();  // ..
    const Token& second = cur();
    if (second.kind != Tok::Number) {
      error(second, "expected the upper end of the range after '..', found " + describe(second),
            "range 0 .. 90 deg");
      return false;
    }
    take();
    double b = 0;
    if (!read_number(second, &b)) return false;
    std::string ub;
    const Token* ub_tok = nullptr;
    if (!read_unit(&ub, &ub_tok)) return false;
    if (!ua.empty() && !ub.empty() && ua != ub) {
      error_at("E0131", ub_tok->line, ub_tok->col, p,
               "the ends of a range are in different units ('" + ua + "' and '" + ub + "')",
               "write both ends in one unit");
      return false;
    }
    json arr = json::array({literal_json(first, a), literal_json(second, b)});
    out_.positions[p + "/0"] = {first.line, first.col};
    out_.positions[p + "/1"] = {second.line, second.col};
    if (!ua.empty() || !ub.empty()) {
      const Token* ut = ub.empty() ? ua_tok : ub_tok;
      units_.push_back({path_of(p), p, {a, b}, {!ua.empty(), !ub.empty()}, ua.empty() ? ub : ua,
                        ut->line, ut->col});
    }
    target[key] = std::move(arr);
    return true;
  }

  // ( n, n, ... ) [unit]
  bool parse_vector(json& target, const std::string& p, const std::string& key) {
    const Token& open = take();
    set_pos(p, open);
    json arr = json::array();
    std::vector<double> raw;
    if (!at(Tok::RParen)) {
      for (;;) {
        const Token& t = cur();
        if (t.kind != Tok::Number) {
          error(t, "expected a number in the vector, found " + describe(t), "(0, 0, 1)");
          return false;
        }
        take();
        double v = 0;
        if (!read_number(t, &v)) return false;
        out_.positions[p + "/" + std::to_string(arr.size())] = {t.line, t.col};
        arr.push_back(literal_json(t, v));
        raw.push_back(v);
        if (at(Tok::Comma)) {
          take();
          continue;
        }
        if (at(Tok::RParen)) break;
        error(cur(), "expected ',' or ')' in the vector, found " + describe(cur()),
              "numbers in a vector are separated by commas: (0, 0, 1)");
        return false;
      }
    }
    take();  // )
    std::string unit;
    const Token* unit_tok = nullptr;
    if (!read_unit(&unit, &unit_tok)) return false;
    if (!unit.empty())
      units_.push_back({path_of(p), p, raw, std::vector<bool>(raw.size(), true), unit,
                        unit_tok->line, unit_tok->col});
    target[key] = std::move(arr);
    return true;
  }

  // A JSON value (the value of an x- key, or a [ ] list): JSON syntax.
  bool parse_json(json& out, const std::string& p) {
    const Token& t = cur();
    switch (t.kind) {
      case Tok::String:
        take();
        out = t.text;
        out_.positions[p] = {t.line, t.col};
        return true;
      case Tok::Number: {
        take();
        out_.positions[p] = {t.line, t.col};
        // Integers stay integers (as the JSON reader keeps them).
        if (auto i = integer_literal(t)) {
          out = std::move(*i);
          return true;
        }
        double v = 0;
        if (!read_number(t, &v)) return false;
        out = v;
        return true;
      }
      case Tok::Ident:
        if (t.text == "true" || t.text == "false" || t.text == "null") {
          take();
          out_.positions[p] = {t.line, t.col};
          if (t.text == "null")
            out = nullptr;
          else
            out = t.text == "true";
          return true;
        }
        error(t, "expected a JSON value, found " + describe(t),
              "an x- field's value is JSON: \"text\", 3, true, null, [ ... ] or { \"k\": ... }");
        return false;
      case Tok::LBracket: {
        take();
        enter(t);
        out = json::array();
        out_.positions[p] = {t.line, t.col};
        if (at(Tok::RBracket)) {
          take();
          leave();
          return true;
        }
        for (;;) {
          json item;
          if (!parse_json(item, p + "/" + std::to_string(out.size()))) return false;
          out.push_back(std::move(item));
          if (at(Tok::Comma)) {
            take();
            continue;
          }
          if (at(Tok::RBracket)) {
            take();
            leave();
            return true;
          }
          error(cur(), "expected ',' or ']' in a JSON list, found " + describe(cur()));
          return false;
        }
      }
      case Tok::LBrace: {
        take();
        enter(t);
        out = json::object();
        out_.positions[p] = {t.line, t.col};
        if (at(Tok::RBrace)) {
          take();
          leave();
          return true;
        }
        for (;;) {
          const Token& k = cur();
          if (k.kind != Tok::String || peek().kind != Tok::Colon) {
            error(k, "expected \"key\": value in a JSON object, found " + describe(k));
            return false;
          }
          take();
          take();
          const std::string kp = pointer_append(p, k.text);
          if (out.contains(k.text)) {
            error_at("E0007", k.line, k.col, kp, "duplicate key '" + k.text + "'",
                     "keep one of them");
            return false;
          }
          out_.positions[key_position(kp)] = {k.line, k.col};
          json item;
          if (!parse_json(item, kp)) return false;
          out[k.text] = std::move(item);
          if (at(Tok::Comma)) {
            take();
            continue;
          }
          if (at(Tok::RBrace)) {
            take();
            leave();
            return true;
          }
          error(cur(), "expected ',' or '}' in a JSON object, found " + describe(cur()));
          return false;
        }
      }
      case Tok::Error:
        error(t, "");
        return false;
      default:
        error(t, "expected a JSON value, found " + describe(t));
        return false;
    }
  }

  // ------------------------------------------------------------ units
  // Checks each written unit against its field's dimension and converts the
  // numbers to the spec's SI values in place.
  void apply_units() {
    if (units_.empty()) return;
    const FieldDimensions dims(out_.value);
    for (const UnitUse& u : units_) {
      const Unit* unit = find_unit(u.unit);
      const Dim dim = dims.of(u.path);
      if (!unit_fits(*unit, dim)) {
        std::string field = u.path.empty() ? std::string("this field") : "'" + u.path.back() + "'";
        error_at("E0131", u.line, u.col, u.pointer,
                 "unit '" + u.unit + "' does not fit " + field + ", which is " + describe_dim(dim),
                 dim == Dim::None ? "write the number without a unit"
                                  : "write it in one of the units shown, or as a bare SI number");
        continue;
      }
      json* node = locate(u.path);
      if (!node) continue;
      if (node->is_array()) {
        for (size_t k = 0; k < u.raw.size() && k < node->size(); ++k)
          (*node)[k] = number_json(to_si(*unit, u.raw[k], dim));
      } else if (!u.raw.empty()) {
        *node = number_json(to_si(*unit, u.raw[0], dim));
      }
    }
  }

  json* locate(const std::vector<std::string>& path) {
    json* node = &out_.value;
    for (const auto& tok : path) {
      if (node->is_object()) {
        auto it = node->find(tok);
        if (it == node->end()) return nullptr;
        node = &*it;
      } else if (node->is_array()) {
        size_t idx = std::strtoul(tok.c_str(), nullptr, 10);
        if (idx >= node->size()) return nullptr;
        node = &(*node)[idx];
      } else {
        return nullptr;
      }
    }
    return node;
  }

  static constexpr size_t kMaxErrors = 200;

  std::string_view text_;
  std::string file_;
  size_t max_depth_;
  Diagnostics& diags_;
  std::vector<Token> toks_;
  std::vector<Comment> comments_list_;
  size_t i_ = 0;
  size_t depth_ = 0;
  size_t errors_ = 0;
  bool unwinding_ = false;  // closing blocks up to the object's after a missing '}'
  frontend::PositionedJson out_;
  std::vector<UnitUse> units_;
  std::vector<StatementStart> statements_;
};

}  // namespace

std::optional<frontend::PositionedJson> parse_with_comments(std::string_view text,
                                                            const std::string& file,
                                                            size_t max_depth, Diagnostics& diags,
                                                            CommentMap* comments) {
  size_t bad = frontend::first_invalid_utf8(text);
  if (bad != std::string_view::npos) {
    int line = 1, col = 1;
    for (size_t i = 0; i < bad; ++i) {
      unsigned char c = static_cast<unsigned char>(text[i]);
      if (c == '\n') {
        ++line;
        col = 1;
      } else if ((c & 0xC0) != 0x80) {
        ++col;
      }
    }
    diags.error("E0004", file, line, col, "", "the file is not UTF-8 text",
                "save the file as UTF-8; is this a binary file?");
    return std::nullopt;
  }
  Diagnostics local;
  auto result = Parser(text, file, max_depth, local).run(comments);
  local.attach_source_lines(file, text);
  for (const auto& d : local.items()) diags.add(d);
  return result;
}

std::optional<frontend::PositionedJson> parse(std::string_view text, const std::string& file,
                                              size_t max_depth, Diagnostics& diags) {
  return parse_with_comments(text, file, max_depth, diags, nullptr);
}

}  // namespace efc::dsl
