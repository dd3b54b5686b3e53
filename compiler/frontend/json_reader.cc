// The JSON front-end's entry points: text -> positioned DOM
// (positioned_json.cc) -> IR with shape checks (spec_builder.cc).
#include "compiler/frontend/json_reader.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "compiler/frontend/positioned_json.h"
#include "compiler/frontend/spec_builder.h"

namespace efc {

bool is_valid_name(std::string_view name) {
  if (name.empty() || name.size() > 64) return false;
  auto alpha = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; };
  if (!alpha(name[0])) return false;
  for (char c : name)
    if (!alpha(c) && !(c >= '0' && c <= '9')) return false;
  return true;
}

std::optional<Object> read_json_text(std::string_view text, const std::string& file,
                                     const std::string& base_dir, const ReadOptions& opts,
                                     Diagnostics& diags) {
  // Collected locally so they can be put in file order (the DOM's objects
  // iterate keys alphabetically, not as written).
  Diagnostics local;
  auto parsed = frontend::parse_positioned(text, file, opts.max_depth, local);
  std::optional<Object> result;
  if (parsed) {
    Object obj;
    obj.file = file;
    obj.base_dir = base_dir;
    obj.positions = std::move(parsed->positions);
    frontend::build_object(parsed->value, obj, opts, local);
    result = std::move(obj);
  }
  std::vector<Diagnostic> items = local.items();
  std::stable_sort(items.begin(), items.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::make_pair(a.line, a.col) < std::make_pair(b.line, b.col);
  });
  for (auto& d : items) diags.add(std::move(d));
  // A document with shape errors is not handed on: check() would only repeat
  // them as confusing follow-up errors.
  if (local.has_errors()) return std::nullopt;
  return result;
}

std::optional<Object> read_json_file(const std::string& path, const ReadOptions& opts,
                                     Diagnostics& diags, bool* io_error) {
  namespace fs = std::filesystem;
  if (io_error) *io_error = false;
  auto fail = [&](const std::string& why) -> std::optional<Object> {
    diags.error("E0001", path, 0, 0, "", "cannot read '" + path + "': " + why);
    if (io_error) *io_error = true;
    return std::nullopt;
  };
  std::error_code ec;
  auto st = fs::status(path, ec);
  if (ec || !fs::exists(st)) return fail("no such file");
  if (fs::is_directory(st)) return fail("it is a folder");
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail("permission denied or unreadable");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return fail("read error");
  std::string base = fs::path(path).parent_path().string();
  if (base.empty()) base = ".";
  return read_json_text(ss.str(), path, base, opts, diags);
}

}  // namespace efc
