// meta.json: read through the positioned JSON reader so every problem is at
// its line:col with its JSON pointer, checked against the rules of
// grammar/sequence-meta.schema.json (kept here too: the schema cannot locate
// errors), and written back in a fixed key order.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "compiler/frontend/json_reader.h"
#include "compiler/frontend/positioned_json.h"
#include "compiler/frontend/suggest.h"
#include "sequence/sequence.h"

namespace efc::seq {
namespace {

using nlohmann::json;
using Keys = std::vector<std::string>;
using frontend::json_kind_phrase;

constexpr const char* kCode = "E1002";
const Keys kTopKeys = {"efc_sequence", "fps",    "width",    "height",    "intrinsics", "depth_scale",
                       "frames",       "gravity", "parts",   "functions", "source"};
const Keys kIntrinsicsKeys = {"fx", "fy", "cx", "cy"};
const Keys kFunctionKeys = {"name", "receptor", "effector"};
const Keys kRoles = {"receptor", "effector", "receptor+effector", "object", "hand"};

std::string last_token(const std::string& ptr) { return ptr.substr(ptr.rfind('/') + 1); }

bool contains(const Keys& keys, const std::string& k) {
  return std::find(keys.begin(), keys.end(), k) != keys.end();
}

// The document -> Meta, one located E1002 per problem.
class MetaReader {
 public:
  MetaReader(const std::string& file, const frontend::Positions& positions, Diagnostics& diags)
      : file_(file), positions_(positions), diags_(diags) {}

  void read(const json& doc, Meta* out) {
    if (!doc.is_object()) {
      err("", "meta.json must be a JSON object, got " + json_kind_phrase(doc),
          "it looks like {\"efc_sequence\": 1, \"fps\": 30, \"width\": 640, ...}");
      return;
    }
    // Unknown keys: "x-" extensions are kept, anything else is a typo.
    for (auto it = doc.begin(); it != doc.end(); ++it) {
      if (contains(kTopKeys, it.key())) continue;
      if (it.key().rfind("x-", 0) == 0) {
        out->extra[it.key()] = it.value();
        continue;
      }
      unknown_key("", it.key(), kTopKeys, "meta.json");
    }
    if (const json* v = get(doc, "", "efc_sequence", true)) {
      if (v->is_number() && v->get<double>() == 1)
        out->version = 1;
      else
        err("/efc_sequence", "unsupported sequence format version " + v->dump() + " (this reader reads 1)",
            "write \"efc_sequence\": 1");
    }
    real(doc, "", "fps", true, Sign::Positive, &out->fps);
    integer(doc, "", "width", &out->width);
    integer(doc, "", "height", &out->height);
    integer(doc, "", "frames", &out->frames);
    real(doc, "", "depth_scale", false, Sign::Positive, &out->depth_scale);
    if (const json* v = get(doc, "", "intrinsics", true)) intrinsics(*v, "/intrinsics", &out->intrinsics);
    if (const json* v = get(doc, "", "gravity", false)) gravity(*v, "/gravity", &out->gravity);
    if (const json* v = get(doc, "", "source", false)) {
      if (v->is_string())
        out->source = v->get<std::string>();
      else
        type_err("/source", *v, "a string");
    }
    // Functions are checked against "parts" only when it is given and sound
    // (a wrong part would otherwise be reported again by every function).
    const json* parts = get(doc, "", "parts", false);
    const bool parts_ok = parts && read_parts(*parts, &out->parts);
    if (const json* v = get(doc, "", "functions", false))
      read_functions(*v, parts_ok, out->parts, &out->functions);
  }

 private:
  enum class Sign { Any, Positive };

  std::pair<int, int> pos_of(std::string ptr) const {
    for (;;) {
      auto it = positions_.find(ptr);
      if (it != positions_.end()) return it->second;
      if (ptr.empty()) return {0, 0};
      ptr = ptr.substr(0, ptr.rfind('/'));
    }
  }
  void err(const std::string& ptr, std::string msg, std::string hint = {}) {
    auto p = pos_of(ptr);
    diags_.error(kCode, file_, p.first, p.second, ptr, std::move(msg), std::move(hint));
  }
  // At the key, not its value: the key is what is wrong.
  void unknown_key(const std::string& ptr, const std::string& key, const Keys& allowed,
                   const std::string& where) {
    const std::string kp = frontend::pointer_append(ptr, key);
    auto it = positions_.find(frontend::key_position(kp));
    auto p = it != positions_.end() ? it->second : pos_of(kp);
    std::string hint = frontend::did_you_mean(key, allowed);
    if (hint.empty() && ptr.empty()) hint = "keys of your own start with \"x-\"";
    diags_.error(kCode, file_, p.first, p.second, kp, "unknown key '" + key + "' in " + where, hint);
  }
  void type_err(const std::string& ptr, const json& v, const std::string& want) {
    err(ptr, "'" + last_token(ptr) + "' must be " + want + ", got " + json_kind_phrase(v));
  }
  const json* get(const json& obj, const std::string& ptr, const char* key, bool required) {
    auto it = obj.find(key);
    if (it != obj.end()) return &*it;
    if (required) err(frontend::pointer_append(ptr, key), std::string("missing required key '") + key + "'");
    return nullptr;
  }

  void real(const json& obj, const std::string& ptr, const char* key, bool required, Sign sign,
            double* out) {
    const json* v = get(obj, ptr, key, required);
    if (!v) return;
    const std::string p = frontend::pointer_append(ptr, key);
    if (!v->is_number()) return type_err(p, *v, "a number");
    const double x = v->get<double>();
    if (sign == Sign::Positive && !(x > 0)) return err(p, "'" + std::string(key) + "' must be > 0, got " + v->dump());
    *out = x;
  }
  // A count or a size: JSON Schema's "integer" (640 or 640.0), at least 1.
  void integer(const json& obj, const std::string& ptr, const char* key, int* out) {
    const json* v = get(obj, ptr, key, true);
    if (!v) return;
    const std::string p = frontend::pointer_append(ptr, key);
    if (!v->is_number()) return type_err(p, *v, "an integer");
    const double x = v->get<double>();
    if (x != std::floor(x)) return type_err(p, *v, "an integer");
    if (x < 1 || x > std::numeric_limits<int>::max())
      return err(p, "'" + std::string(key) + "' must be an integer >= 1, got " + v->dump());
    *out = static_cast<int>(x);
  }

  void intrinsics(const json& v, const std::string& ptr, Intrinsics* out) {
    if (!v.is_object()) return type_err(ptr, v, "an object {\"fx\", \"fy\", \"cx\", \"cy\"}");
    for (auto it = v.begin(); it != v.end(); ++it)
      if (!contains(kIntrinsicsKeys, it.key())) unknown_key(ptr, it.key(), kIntrinsicsKeys, "'intrinsics'");
    real(v, ptr, "fx", true, Sign::Positive, &out->fx);
    real(v, ptr, "fy", true, Sign::Positive, &out->fy);
    real(v, ptr, "cx", true, Sign::Any, &out->cx);
    real(v, ptr, "cy", true, Sign::Any, &out->cy);
  }

  void gravity(const json& v, const std::string& ptr, std::array<double, 3>* out) {
    if (!v.is_array() || v.size() != 3) return type_err(ptr, v, "an array of 3 numbers");
    std::array<double, 3> g{};
    for (size_t i = 0; i < 3; ++i) {
      if (!v[i].is_number()) return type_err(ptr + "/" + std::to_string(i), v[i], "a number");
      g[i] = v[i].get<double>();
    }
    if (g[0] == 0 && g[1] == 0 && g[2] == 0)
      return err(ptr, "'gravity' is [0, 0, 0]; it must be a direction", "the default is [0, 0, -1] (z up)");
    *out = g;
  }

  // "parts": {name: role}, kept in file order (the DOM sorts keys).
  bool read_parts(const json& v, std::vector<std::pair<std::string, std::string>>* out) {
    if (!v.is_object()) {
      type_err("/parts", v, "an object {\"part name\": \"role\"}");
      return false;
    }
    bool ok = true;
    std::vector<std::pair<std::pair<int, int>, std::pair<std::string, std::string>>> found;
    for (auto it = v.begin(); it != v.end(); ++it) {
      const std::string p = frontend::pointer_append("/parts", it.key());
      if (!is_valid_name(it.key())) {
        auto kp = positions_.find(frontend::key_position(p));
        auto at = kp != positions_.end() ? kp->second : pos_of(p);
        diags_.error(kCode, file_, at.first, at.second, p,
                     "part name '" + it.key() + "' is not a name (letters, digits, '_'; not starting with a digit)",
                     "part names are the spec's part names; they name mask folders too");
        ok = false;
        continue;
      }
      if (!it.value().is_string()) {
        type_err(p, it.value(), "a role (a string)");
        ok = false;
        continue;
      }
      const std::string role = it.value().get<std::string>();
      if (!contains(kRoles, role)) {
        std::string hint = frontend::did_you_mean(role, kRoles);
        err(p, "unknown role '" + role + "' (receptor, effector, receptor+effector, object, hand)", hint);
        ok = false;
        continue;
      }
      found.push_back({pos_of(p), {it.key(), role}});
    }
    std::stable_sort(found.begin(), found.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto& f : found) out->push_back(std::move(f.second));
    return ok;
  }

  void read_functions(const json& v, bool have_parts,
                      const std::vector<std::pair<std::string, std::string>>& parts,
                      std::vector<FunctionRef>* out) {
    if (!v.is_array()) return type_err("/functions", v, "an array");
    for (size_t i = 0; i < v.size(); ++i) {
      const std::string ptr = "/functions/" + std::to_string(i);
      const json& f = v[i];
      if (!f.is_object()) {
        type_err(ptr, f, "an object {\"name\", \"receptor\", \"effector\"}");
        continue;
      }
      for (auto it = f.begin(); it != f.end(); ++it)
        if (!contains(kFunctionKeys, it.key())) unknown_key(ptr, it.key(), kFunctionKeys, "a function");
      FunctionRef ref;
      bool ok = name(f, ptr, "name", &ref.name);
      ok = name(f, ptr, "receptor", &ref.receptor) && ok;
      ok = name(f, ptr, "effector", &ref.effector) && ok;
      if (!ok) continue;
      for (const FunctionRef& earlier : *out)
        if (earlier.name == ref.name) err(ptr + "/name", "duplicate function name '" + ref.name + "'");
      if (ref.receptor == ref.effector)
        err(ptr + "/effector", "function '" + ref.name + "' has the same part as receptor and effector");
      if (have_parts) {
        role_of(parts, ref.receptor, "receptor", ptr + "/receptor");
        role_of(parts, ref.effector, "effector", ptr + "/effector");
      }
      out->push_back(std::move(ref));
    }
  }

  bool name(const json& f, const std::string& ptr, const char* key, std::string* out) {
    const json* v = get(f, ptr, key, true);
    if (!v) return false;
    const std::string p = frontend::pointer_append(ptr, key);
    if (!v->is_string()) {
      type_err(p, *v, "a string");
      return false;
    }
    *out = v->get<std::string>();
    if (!is_valid_name(*out)) {
      err(p, "'" + *out + "' is not a name (letters, digits, '_'; not starting with a digit)");
      return false;
    }
    return true;
  }

  // A function's receptor must be a listed part that can act as one
  // (receptor, or the middle of a chain), and likewise its effector.
  void role_of(const std::vector<std::pair<std::string, std::string>>& parts, const std::string& part,
               const std::string& want, const std::string& ptr) {
    auto it = std::find_if(parts.begin(), parts.end(), [&](const auto& p) { return p.first == part; });
    if (it == parts.end()) {
      Keys names;
      for (const auto& p : parts) names.push_back(p.first);
      return err(ptr, "'" + part + "' is not listed in \"parts\"", frontend::did_you_mean(part, names));
    }
    if (it->second != want && it->second != "receptor+effector")
      err(ptr, "'" + part + "' is listed as " + it->second + " in \"parts\", not as " + want,
          "a part that is both (a chain's middle) is \"receptor+effector\"");
  }

  const std::string& file_;
  const frontend::Positions& positions_;
  Diagnostics& diags_;
};

// Integral values as JSON integers ("fps": 30, not 30.0): the file reads as a
// person would write it, and reads back to the same double.
nlohmann::ordered_json number(double v) {
  if (std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 9e15)
    return static_cast<long long>(v);
  return v;
}

}  // namespace

bool read_meta_text(const std::string& text, const std::string& file, Diagnostics& diags, Meta* out) {
  *out = Meta();
  Diagnostics local;
  if (auto parsed = frontend::parse_positioned(text, file, 256, local))
    MetaReader(file, parsed->positions, local).read(parsed->value, out);
  // In file order (the DOM iterates keys alphabetically), quoting the line.
  std::vector<Diagnostic> items = local.items();
  std::stable_sort(items.begin(), items.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::make_pair(a.line, a.col) < std::make_pair(b.line, b.col);
  });
  Diagnostics sorted;
  for (auto& d : items) {
    if (d.code == "E0002") d.hint = "meta.json looks like {\"efc_sequence\": 1, \"fps\": 30, ...}";  // not a spec's hint
    sorted.add(std::move(d));
  }
  sorted.attach_source_lines(file, text);
  for (const auto& d : sorted.items()) diags.add(d);
  return !sorted.has_errors();
}

bool read_meta(const std::string& meta_path, Diagnostics& diags, Meta* out) {
  std::error_code ec;
  std::ifstream in;
  if (std::filesystem::is_regular_file(meta_path, ec)) in.open(meta_path, std::ios::binary);
  std::string text(std::istreambuf_iterator<char>(in), {});
  if (!in.is_open() || in.bad()) {
    *out = Meta();
    diags.error("E1001", meta_path, 0, 0, "", "cannot read meta.json (missing, a folder, or not readable)",
                "a sequence folder holds meta.json (shared/spec/sequence.md)");
    return false;
  }
  return read_meta_text(text, meta_path, diags, out);
}

std::string meta_to_json_text(const Meta& meta) {
  nlohmann::ordered_json j;
  j["efc_sequence"] = meta.version;
  j["fps"] = number(meta.fps);
  j["width"] = meta.width;
  j["height"] = meta.height;
  j["intrinsics"] = {{"fx", number(meta.intrinsics.fx)},
                     {"fy", number(meta.intrinsics.fy)},
                     {"cx", number(meta.intrinsics.cx)},
                     {"cy", number(meta.intrinsics.cy)}};
  j["depth_scale"] = number(meta.depth_scale);
  j["frames"] = meta.frames;
  j["gravity"] = {number(meta.gravity[0]), number(meta.gravity[1]), number(meta.gravity[2])};
  if (!meta.parts.empty()) {
    nlohmann::ordered_json parts = nlohmann::ordered_json::object();
    for (const auto& [name, role] : meta.parts) parts[name] = role;
    j["parts"] = parts;
  }
  if (!meta.functions.empty()) {
    nlohmann::ordered_json fns = nlohmann::ordered_json::array();
    for (const auto& f : meta.functions)
      fns.push_back({{"name", f.name}, {"receptor", f.receptor}, {"effector", f.effector}});
    j["functions"] = fns;
  }
  if (!meta.source.empty()) j["source"] = meta.source;
  for (auto it = meta.extra.begin(); it != meta.extra.end(); ++it)
    if (!j.contains(it.key())) j[it.key()] = nlohmann::ordered_json::parse(it.value().dump());
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

bool write_meta(const std::string& meta_path, const Meta& meta, std::string* error) {
  for (auto it = meta.extra.begin(); it != meta.extra.end(); ++it)
    if (it.key().rfind("x-", 0) != 0) {
      *error = "meta.extra key '" + it.key() + "' does not start with \"x-\"";
      return false;
    }
  // Whatever is written must read back: check the text with the reader.
  const std::string text = meta_to_json_text(meta);
  Diagnostics check;
  Meta reread;
  if (!read_meta_text(text, meta_path, check, &reread)) {
    for (const auto& d : check.items())
      if (d.severity == Severity::Error) {
        *error = "would write an invalid meta.json: " + d.message;
        break;
      }
    return false;
  }
  return write_text_file(meta_path, text, error);
}

}  // namespace efc::seq
