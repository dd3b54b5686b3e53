// The DSL printer: a spec document -> canonical .efc text, and canonical JSON.
//
// The printer is the inverse of the parser for every document the parser can
// build, not only valid specs: what has no sugar (a geometry that is not an
// object, a list of words) falls back to a quoted key and a JSON value, so
// parse(print(doc)) == doc always. Numbers are spelled in the unit that reads
// back exactly and is shortest (dsl_units.h). Canonical layout: one statement
// per line; a block whose statements are all one-liners goes on one line when
// it fits in 80 columns; a blank line between multi-line items of the object.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "compiler/frontend/dsl.h"
#include "compiler/frontend/dsl_syntax.h"
#include "compiler/frontend/dsl_units.h"
#include "compiler/frontend/positioned_json.h"

namespace efc::dsl {
namespace {

using nlohmann::json;


// Spelled as a bare identifier, the lexer gives back the same word.
bool ident_ok(const std::string& s) {
  if (s.empty() || !is_letter(s[0])) return false;
  for (char c : s)
    if (!is_letter(c) && !is_digit(c)) return false;
  return true;
}
bool word_ok(const json& v) {
  if (!v.is_string()) return false;
  const std::string s = v.get<std::string>();
  return ident_ok(s) && s != "true" && s != "false" && s != "null";
}
// x-... keys the lexer reads as one Extension token.
bool extension_ok(const std::string& s) {
  if (s.size() < 3 || s.rfind("x-", 0) != 0 || !(is_letter(s[2]) || is_digit(s[2]))) return false;
  for (size_t i = 2; i < s.size(); ++i) {
    char c = s[i];
    if (!is_letter(c) && !is_digit(c) && c != '-' && c != '.') return false;
    if (c == '-' && i + 1 < s.size() && s[i + 1] == '>') return false;
  }
  return true;
}

std::string quoted(const std::string& s) {
  return json(s).dump(-1, ' ', false, json::error_handler_t::replace);
}
std::string json_literal(const json& v) {
  return v.dump(-1, ' ', false, json::error_handler_t::replace);
}

// A scalar as JSON; integral floats are written as integers (2, not 2.0),
// so the text does not depend on whether the document came from JSON or DSL.
std::string json_scalar(const json& v) {
  if (v.is_number_float()) {
    const double d = v.get<double>();
    if (std::isfinite(d) && d == std::floor(d) && std::fabs(d) <= 9007199254740992.0 &&
        !(d == 0 && std::signbit(d)))
      return std::to_string(static_cast<long long>(d));
  }
  return json_literal(v);
}

// Compact JSON for x- values and fallbacks, numbers as json_scalar writes them.
std::string compact_json(const json& v) {
  if (v.is_object()) {
    std::string out = "{";
    bool first = true;
    for (auto it = v.begin(); it != v.end(); ++it) {
      out += (first ? "" : ", ") + quoted(it.key()) + ": " + compact_json(it.value());
      first = false;
    }
    return out + "}";
  }
  if (v.is_array()) {
    std::string out = "[";
    for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + compact_json(v[i]);
    return out + "]";
  }
  return json_scalar(v);
}

// True when a double holds the number exactly (integers beyond 2^53 may not).
bool exact_as_double(const json& v) {
  if (v.is_number_integer() && !v.is_number_unsigned()) {
    const std::int64_t i = v.get<std::int64_t>();
    return i >= -9007199254740992LL && i <= 9007199254740992LL;
  }
  if (v.is_number_unsigned()) return v.get<std::uint64_t>() <= 9007199254740992ULL;
  return v.is_number();
}

std::string key_text(const std::string& key, Ctx ctx) {
  // `part` and `function` are quoted everywhere: at the start of a line the
  // parser takes them for a new part or function after a missing '}'.
  if (ident_ok(key) && !is_keyword(ctx, key) && key != "part" && key != "function") return key;
  if (extension_ok(key)) return key;
  return quoted(key);
}

// Canonical key order inside an object, by the key it sits under ("" for
// the document, "parts" for a part, "geometry" for a geometry, ...).
const std::vector<std::string>& order_for(const std::string& container) {
  static const std::map<std::string, std::vector<std::string>> orders = {
      {"", {"efc", "name", "description", "parts", "functions"}},
      {"parts", {"name", "role", "geometry", "mass", "rgba", "joint"}},
      {"geometry", {"box", "cylinder", "sphere", "mesh", "compound", "scale"}},
      {"compound", {"box", "cylinder", "sphere", "mesh", "compound", "scale"}},
      {"box", {"size", "center", "rpy"}},
      {"cylinder", {"radius", "length", "center", "axis"}},
      {"sphere", {"radius", "center"}},
      {"joint", {"type", "parent", "axis", "origin", "range", "initial", "damping", "friction",
                 "spring"}},
      {"spring", {"stiffness", "rest"}},
      {"functions", {"name", "receptor", "effector", "mapping", "effect"}},
      {"mapping", {"type", "threshold", "hysteresis", "latching", "gain", "offset", "delta",
                   "initial"}},
      {"effect", {"type", "range", "stiffness", "damping", "color", "position", "time_constant",
                  "emitter", "speed", "droplet_radius", "outlet", "cone_angle", "reach"}},
      {"emitter", {"position", "direction"}},
      {"outlet", {"position", "direction"}},
  };
  static const std::vector<std::string> none;
  auto it = orders.find(container);
  return it == orders.end() ? none : it->second;
}

std::vector<std::string> ordered_keys(const json& obj, const std::string& container) {
  std::vector<std::string> out;
  for (const auto& k : order_for(container))
    if (obj.contains(k)) out.push_back(k);
  for (auto it = obj.begin(); it != obj.end(); ++it)
    if (std::find(out.begin(), out.end(), it.key()) == out.end()) out.push_back(it.key());
  return out;
}

std::string join_pointer(const std::vector<std::string>& path) {
  std::string p;
  for (const auto& t : path) p = frontend::pointer_append(p, t);
  return p;
}

struct Stmt {
  std::string head;
  bool has_block = false;
  std::vector<Stmt> body;
  std::vector<std::string> pointers;  // the comments of any of these belong here
};

class Printer {
 public:
  Printer(const json& doc, const CommentMap* comments)
      : doc_(doc), comments_(comments), dims_(doc) {}

  std::string run() {
    std::vector<Stmt> top;
    if (doc_.contains("efc")) top.push_back(generic("efc", doc_["efc"], {"efc"}, Ctx::Generic));
    top.push_back(object_statement());
    std::vector<std::string> lines;
    for (size_t i = 0; i < top.size(); ++i) {
      if (i > 0) lines.push_back("");
      render(top[i], 0, lines);
    }
    // Comments whose statement is gone (the sugar changed): kept at the end.
    std::vector<std::string> rest;
    if (comments_) {
      for (const auto& [p, texts] : comments_->leading)
        if (!used_.count("L" + p))
          for (const auto& t : texts) rest.push_back(t);
      for (const auto& [p, t] : comments_->trailing)
        if (!used_.count("T" + p)) rest.push_back(t);
      for (const auto& t : comments_->file_end) rest.push_back(t);
    }
    if (!rest.empty()) lines.push_back("");
    for (const auto& t : rest) lines.push_back("#" + t);
    std::string out;
    for (const auto& l : lines) out += l + "\n";
    return out;
  }

 private:
  // ------------------------------------------------------------ structure
  Stmt object_statement() {
    Stmt s;
    s.head = "object";
    s.pointers = {""};
    s.has_block = true;
    std::set<std::string> skip{"efc"};
    if (word_ok(doc_.value("name", json()))) {
      s.head += " " + doc_["name"].get<std::string>();
      skip.insert("name");
    }
    for (const auto& k : ordered_keys(doc_, "")) {
      if (skip.count(k)) continue;
      const json& v = doc_[k];
      if ((k == "parts" || k == "functions") && v.is_array() && !v.empty() &&
          std::all_of(v.begin(), v.end(), [](const json& e) { return e.is_object(); })) {
        for (size_t i = 0; i < v.size(); ++i)
          s.body.push_back(k == "parts" ? part_statement(v[i], i) : function_statement(v[i], i));
        continue;
      }
      s.body.push_back(generic(k, v, {k}, Ctx::Object));
    }
    return s;
  }

  Stmt part_statement(const json& part, size_t i) {
    const std::vector<std::string> path{"parts", std::to_string(i)};
    Stmt s;
    s.head = "part";
    s.has_block = true;
    s.pointers = {join_pointer(path)};
    std::set<std::string> skip;
    if (word_ok(part.value("name", json()))) {
      s.head += " " + part["name"].get<std::string>();
      skip.insert("name");
      if (word_ok(part.value("role", json()))) {
        s.head += ": " + part["role"].get<std::string>();
        skip.insert("role");
      }
    }
    for (const auto& k : ordered_keys(part, "parts")) {
      if (skip.count(k)) continue;
      auto p = path;
      p.push_back(k);
      const json& v = part[k];
      if (k == "geometry" && v.is_object())
        s.body.push_back(geometry_statement(v, p));
      else if (k == "joint" && v.is_object())
        s.body.push_back(headed("joint", v, p));
      else
        s.body.push_back(generic(k, v, p, Ctx::Part));
    }
    return s;
  }

  Stmt function_statement(const json& fn, size_t i) {
    const std::vector<std::string> path{"functions", std::to_string(i)};
    Stmt s;
    s.head = "function";
    s.has_block = true;
    s.pointers = {join_pointer(path)};
    std::set<std::string> skip;
    if (word_ok(fn.value("name", json()))) {
      s.head += " " + fn["name"].get<std::string>();
      skip.insert("name");
      if (word_ok(fn.value("receptor", json())) && word_ok(fn.value("effector", json()))) {
        s.head += ": " + fn["receptor"].get<std::string>() + " -> " +
                  fn["effector"].get<std::string>();
        skip.insert("receptor");
        skip.insert("effector");
      }
    }
    for (const auto& k : ordered_keys(fn, "functions")) {
      if (skip.count(k)) continue;
      auto p = path;
      p.push_back(k);
      const json& v = fn[k];
      if ((k == "mapping" || k == "effect") && v.is_object())
        s.body.push_back(headed(k, v, p));
      else
        s.body.push_back(generic(k, v, p, Ctx::Function));
    }
    return s;
  }

  // joint TYPE on PARENT { ... }, mapping TYPE { ... }, effect TYPE { ... }
  Stmt headed(const std::string& key, const json& node, const std::vector<std::string>& path) {
    Stmt s;
    s.head = key;
    s.pointers = {join_pointer(path)};
    std::set<std::string> skip;
    const bool joint = key == "joint";
    if (word_ok(node.value("type", json())) && !(joint && node["type"] == "on")) {
      s.head += " " + node["type"].get<std::string>();
      skip.insert("type");
    }
    if (joint && word_ok(node.value("parent", json()))) {
      s.head += " on " + node["parent"].get<std::string>();
      skip.insert("parent");
    }
    for (const auto& k : ordered_keys(node, key)) {
      if (skip.count(k)) continue;
      auto p = path;
      p.push_back(k);
      s.body.push_back(generic(k, node[k], p, Ctx::Generic));
    }
    s.has_block = !s.body.empty();
    return s;
  }

  // A geometry object (a part's, or a compound element) with its sugar.
  Stmt geometry_statement(const json& w, const std::vector<std::string>& path) {
    const std::string wp = join_pointer(path);
    if (w.size() == 1) {
      const std::string kind = w.begin().key();
      const json& v = w.begin().value();
      if ((kind == "box" || kind == "cylinder" || kind == "sphere") && v.is_object()) {
        auto p = path;
        p.push_back(kind);
        Stmt s = generic(kind, v, p, Ctx::Generic);
        s.pointers.push_back(wp);
        return s;
      }
      if (kind == "compound" && compound_ok(v)) {
        auto p = path;
        p.push_back(kind);
        Stmt s = compound_statement(v, p);
        s.pointers.push_back(wp);
        return s;
      }
    }
    if (w.contains("mesh") && w["mesh"].is_string()) {
      auto p = path;
      p.push_back("mesh");
      Stmt s;
      s.head = "mesh " + quoted(w["mesh"].get<std::string>());
      s.pointers = {join_pointer(p), wp};
      for (const auto& k : ordered_keys(w, "geometry"))
        if (k != "mesh") s.body.push_back(wrapper_item(w, k, path));
      s.has_block = !s.body.empty();
      return s;
    }
    Stmt s;
    s.head = "geometry";
    s.has_block = true;
    s.pointers = {wp};
    for (const auto& k : ordered_keys(w, "geometry")) s.body.push_back(wrapper_item(w, k, path));
    return s;
  }

  static bool compound_ok(const json& v) {
    return v.is_array() &&
           std::all_of(v.begin(), v.end(), [](const json& e) { return e.is_object(); });
  }

  Stmt compound_statement(const json& elements, const std::vector<std::string>& path) {
    Stmt s;
    s.head = "compound";
    s.has_block = true;
    s.pointers = {join_pointer(path)};
    for (size_t i = 0; i < elements.size(); ++i) {
      auto p = path;
      p.push_back(std::to_string(i));
      s.body.push_back(geometry_statement(elements[i], p));
    }
    return s;
  }

  // One key of a geometry object, inside `geometry { }` or a mesh's block.
  Stmt wrapper_item(const json& w, const std::string& k, const std::vector<std::string>& path) {
    auto p = path;
    p.push_back(k);
    const json& v = w[k];
    if ((k == "box" || k == "cylinder" || k == "sphere") && v.is_object())
      return generic(k, v, p, Ctx::Generic);
    if (k == "mesh" && v.is_string()) {
      Stmt s;
      s.head = "mesh " + quoted(v.get<std::string>());
      s.pointers = {join_pointer(p)};
      return s;
    }
    if (k == "compound" && compound_ok(v)) return compound_statement(v, p);
    return generic(k, v, p, Ctx::Wrapper);
  }

  // key value, or key { ... } for an object. x- keys take JSON values.
  Stmt generic(const std::string& key, const json& v, const std::vector<std::string>& path,
               Ctx ctx) {
    Stmt s;
    s.pointers = {join_pointer(path)};
    const std::string k = key_text(key, ctx);
    if (key.rfind("x-", 0) == 0) {
      s.head = k + " " + compact_json(v);
      return s;
    }
    if (v.is_object()) {
      s.head = k;
      s.has_block = true;
      for (const auto& child : ordered_keys(v, key)) {
        auto p = path;
        p.push_back(child);
        s.body.push_back(generic(child, v[child], p, Ctx::Generic));
      }
      return s;
    }
    s.head = k + " " + value_text(key, v, path);
    return s;
  }

  std::string value_text(const std::string& key, const json& v,
                         const std::vector<std::string>& path) {
    if (v.is_number()) {
      // Integers beyond a double's 53 bits keep their digits (bare: SI).
      if (!exact_as_double(v)) return json_literal(v);
      Spelled sp = spell({v.get<double>()}, dims_.of(path));
      return sp.numbers[0] + (sp.unit.empty() ? "" : " " + sp.unit);
    }
    if (v.is_string()) return quoted(v.get<std::string>());
    if (v.is_array() && !v.empty() &&
        std::all_of(v.begin(), v.end(), [](const json& e) { return exact_as_double(e); })) {
      std::vector<double> values;
      for (const auto& e : v) values.push_back(e.get<double>());
      Spelled sp = spell(values, dims_.of(path));
      const std::string unit = sp.unit.empty() ? "" : " " + sp.unit;
      if (key == "range" && values.size() == 2) return sp.numbers[0] + " .. " + sp.numbers[1] + unit;
      std::string out = "(";
      for (size_t i = 0; i < sp.numbers.size(); ++i) out += (i ? ", " : "") + sp.numbers[i];
      return out + ")" + unit;
    }
    return compact_json(v);  // true, false, null, [], lists of other things
  }

  // ------------------------------------------------------------ layout
  bool has_comments(const Stmt& s) const {
    if (!comments_) return false;
    for (const auto& p : s.pointers)
      if (comments_->leading.count(p) || comments_->trailing.count(p)) return true;
    return false;
  }

  // The whole statement on one line, or "" when it cannot be.
  std::string one_line(const Stmt& s) const {
    if (!s.has_block) return s.head;
    if (s.body.empty()) return s.head + " {}";
    std::string inner;
    for (size_t i = 0; i < s.body.size(); ++i) {
      const Stmt& c = s.body[i];
      if (c.has_block || has_comments(c)) return "";
      inner += (i ? "; " : "") + c.head;
    }
    std::string line = s.head + " { " + inner + " }";
    return line.size() <= 80 ? line : "";
  }

  void render(const Stmt& s, int indent, std::vector<std::string>& lines) {
    const std::string pad(static_cast<size_t>(indent) * 2, ' ');
    std::string trailing;
    if (comments_) {
      for (const auto& p : s.pointers) {
        auto l = comments_->leading.find(p);
        if (l != comments_->leading.end() && used_.insert("L" + p).second)
          for (const auto& t : l->second) lines.push_back(pad + "#" + t);
        auto t = comments_->trailing.find(p);
        if (t != comments_->trailing.end() && trailing.empty() && used_.insert("T" + p).second)
          trailing = "  #" + t->second;
      }
    }
    const std::string line = one_line(s);
    if (!line.empty()) {
      lines.push_back(pad + line + trailing);
      return;
    }
    lines.push_back(pad + s.head + " {" + trailing);
    const bool spaced = s.head.rfind("object", 0) == 0;
    for (size_t i = 0; i < s.body.size(); ++i) {
      const size_t before = lines.size();
      if (spaced && i > 0) {
        // A blank line around multi-line items of the object.
        const bool multi = one_line(s.body[i]).empty() || one_line(s.body[i - 1]).empty();
        if (multi) lines.push_back("");
      }
      (void)before;
      render(s.body[i], indent + 1, lines);
    }
    lines.push_back(pad + "}");
  }

  const json& doc_;
  const CommentMap* comments_;
  const FieldDimensions dims_;
  std::set<std::string> used_;
};

// ------------------------------------------------------------ JSON
void write_json(const json& v, const std::string& container, int indent, std::string& out) {
  const std::string pad(static_cast<size_t>(indent) * 2, ' ');
  const std::string inner(static_cast<size_t>(indent + 1) * 2, ' ');
  if (v.is_object()) {
    if (v.empty()) {
      out += "{}";
      return;
    }
    out += "{\n";
    const auto keys = ordered_keys(v, container);
    for (size_t i = 0; i < keys.size(); ++i) {
      out += inner + quoted(keys[i]) + ": ";
      write_json(v[keys[i]], keys[i], indent + 1, out);
      out += i + 1 < keys.size() ? ",\n" : "\n";
    }
    out += pad + "}";
    return;
  }
  if (v.is_array()) {
    const bool scalars = std::all_of(v.begin(), v.end(), [](const json& e) {
      return !e.is_object() && !e.is_array();
    });
    size_t flat = 2;
    for (const auto& e : v) flat += json_literal(e).size() + 2;
    if (v.empty() || (scalars && flat <= 80)) {
      // [1, 2, 3] rather than [1,2,3]
      out += "[";
      for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + json_scalar(v[i]);
      out += "]";
      return;
    }
    out += "[\n";
    for (size_t i = 0; i < v.size(); ++i) {
      out += inner;
      write_json(v[i], container, indent + 1, out);
      out += i + 1 < v.size() ? ",\n" : "\n";
    }
    out += pad + "]";
    return;
  }
  out += json_scalar(v);
}

}  // namespace

std::string print(const json& doc, const CommentMap* comments) {
  if (!doc.is_object()) return "";
  return Printer(doc, comments).run();
}

std::string print_json(const json& doc) {
  std::string out;
  write_json(doc, "", 0, out);
  return out + "\n";
}

}  // namespace efc::dsl
