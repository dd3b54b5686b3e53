#include "pipeline/egofun3d/json_doc.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace efc::egofun3d {

std::string pointer_join(const std::string& base, const std::string& key) {
  return frontend::pointer_append(base, key);
}
std::string pointer_join(const std::string& base, size_t index) { return base + "/" + std::to_string(index); }

bool JsonDoc::read(const std::string& path, const std::string& code, Diagnostics& diags) {
  file_ = path;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    diags.error(code, path, 0, 0, "", std::filesystem::exists(path, ec) ? "is not a file" : "does not exist");
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  text_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  const std::string& text = text_;
  if (!in && !in.eof()) {
    diags.error(code, path, 0, 0, "", "cannot be read");
    return false;
  }
  const size_t before = diags.error_count();
  // Annotation files nest a few levels; 256 is the specs' own limit.
  auto doc = frontend::parse_positioned(text, path, 256, diags);
  diags.attach_source_lines(path, text);
  if (!doc) return false;
  doc_ = std::move(*doc);
  return diags.error_count() == before;
}

std::pair<int, int> JsonDoc::at(const std::string& pointer) const {
  std::string p = pointer;
  for (;;) {
    auto it = doc_.positions.find(p);
    if (it != doc_.positions.end()) return it->second;
    if (p.empty()) return {1, 1};
    p = p.substr(0, p.rfind('/'));
  }
}

void JsonDoc::error(Diagnostics& diags, const std::string& code, const std::string& pointer,
                    const std::string& message, const std::string& hint) const {
  const auto [line, col] = at(pointer);
  diags.error(code, file_, line, col, pointer, message, hint);
  diags.attach_source_lines(file_, text_);  // the line under the message, with a caret
}

void JsonDoc::warning(Diagnostics& diags, const std::string& code, const std::string& pointer,
                      const std::string& message) const {
  const auto [line, col] = at(pointer);
  diags.warning(code, file_, line, col, pointer, message);
  diags.attach_source_lines(file_, text_);
}

const nlohmann::json* JsonDoc::member(Diagnostics& diags, const std::string& code, const std::string& pointer,
                                      const std::string& key, bool required) const {
  const nlohmann::json* obj = nullptr;
  try {
    obj = &doc_.value.at(nlohmann::json::json_pointer(pointer));
  } catch (const nlohmann::json::exception&) {
    obj = nullptr;
  }
  if (!obj || !obj->is_object()) {
    error(diags, code, pointer, "expected an object with \"" + key + "\", found " +
                                    (obj ? frontend::json_kind_phrase(*obj) : std::string("nothing")));
    return nullptr;
  }
  auto it = obj->find(key);
  if (it == obj->end()) {
    if (required) error(diags, code, pointer, "missing \"" + key + "\"");
    return nullptr;
  }
  return &*it;
}

std::optional<std::string> JsonDoc::string(Diagnostics& diags, const std::string& code,
                                           const std::string& pointer, const std::string& key) const {
  const nlohmann::json* v = member(diags, code, pointer, key);
  if (!v) return std::nullopt;
  if (!v->is_string()) {
    error(diags, code, pointer_join(pointer, key), "\"" + key + "\" must be a string, found " +
                                                       frontend::json_kind_phrase(*v));
    return std::nullopt;
  }
  return v->get<std::string>();
}

std::optional<double> JsonDoc::number(Diagnostics& diags, const std::string& code, const std::string& pointer,
                                      const std::string& key) const {
  const nlohmann::json* v = member(diags, code, pointer, key);
  if (!v) return std::nullopt;
  if (!v->is_number() || !std::isfinite(v->get<double>())) {
    error(diags, code, pointer_join(pointer, key), "\"" + key + "\" must be a finite number, found " +
                                                       frontend::json_kind_phrase(*v));
    return std::nullopt;
  }
  return v->get<double>();
}

std::optional<std::vector<double>> JsonDoc::numbers(Diagnostics& diags, const std::string& code,
                                                    const std::string& pointer, const std::string& key,
                                                    size_t n) const {
  const nlohmann::json* v = member(diags, code, pointer, key);
  if (!v) return std::nullopt;
  const std::string p = pointer_join(pointer, key);
  if (!v->is_array() || v->size() != n) {
    error(diags, code, p, "\"" + key + "\" must be an array of " + std::to_string(n) + " numbers");
    return std::nullopt;
  }
  std::vector<double> out;
  for (size_t i = 0; i < n; ++i) {
    const auto& x = (*v)[i];
    if (!x.is_number() || !std::isfinite(x.get<double>())) {
      error(diags, code, pointer_join(p, i), "element " + std::to_string(i) + " of \"" + key +
                                                 "\" is not a finite number");
      return std::nullopt;
    }
    out.push_back(x.get<double>());
  }
  return out;
}

std::optional<std::array<double, 9>> JsonDoc::matrix3(Diagnostics& diags, const std::string& code,
                                                      const std::string& pointer, const std::string& key) const {
  const nlohmann::json* v = member(diags, code, pointer, key);
  if (!v) return std::nullopt;
  const std::string p = pointer_join(pointer, key);
  const char* shape = "must be a 3x3 matrix: [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]";
  if (!v->is_array() || v->size() != 3) {
    error(diags, code, p, "\"" + key + "\" " + shape);
    return std::nullopt;
  }
  std::array<double, 9> m{};
  for (size_t r = 0; r < 3; ++r) {
    const auto& row = (*v)[r];
    if (!row.is_array() || row.size() != 3) {
      error(diags, code, pointer_join(p, r), "\"" + key + "\" " + shape);
      return std::nullopt;
    }
    for (size_t c = 0; c < 3; ++c) {
      if (!row[c].is_number() || !std::isfinite(row[c].get<double>())) {
        error(diags, code, pointer_join(pointer_join(p, r), c), "not a finite number");
        return std::nullopt;
      }
      m[r * 3 + c] = row[c].get<double>();
    }
  }
  return m;
}

}  // namespace efc::egofun3d
