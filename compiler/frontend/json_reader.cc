// The JSON front-end's entry points: text -> positioned DOM
// (positioned_json.cc) -> IR with shape checks (spec_builder.cc).
#include "compiler/frontend/json_reader.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "compiler/frontend/dsl.h"
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

namespace {

// A parsed document -> the IR with shape checks; diagnostics in file order.
// `value` is null when the text could not be parsed (its errors are in local).
std::optional<Object> build_from(const nlohmann::json* value, frontend::Positions positions,
                                 Diagnostics& local, const std::string& file,
                                 const std::string& base_dir, const ReadOptions& opts,
                                 Diagnostics& diags) {
  std::optional<Object> result;
  if (value) {
    Object obj;
    obj.file = file;
    obj.base_dir = base_dir;
    obj.positions = std::move(positions);
    frontend::build_object(*value, obj, opts, local);
    result = std::move(obj);
  }
  // Put in file order (the DOM's objects iterate keys alphabetically, not as written).
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

// Text of either format (by the file's extension) -> the positioned document.
std::optional<frontend::PositionedJson> parse_any(std::string_view text, const std::string& file,
                                                  const ReadOptions& opts, Diagnostics& local,
                                                  dsl::CommentMap* comments) {
  if (is_dsl_path(file)) return dsl::parse_with_comments(text, file, opts.max_depth, local, comments);
  return frontend::parse_positioned(text, file, opts.max_depth, local);
}

std::string folder_of(const std::string& path) {
  std::string base = std::filesystem::path(path).parent_path().string();
  return base.empty() ? "." : base;
}

}  // namespace

namespace {

// A parse's result (nullopt: its errors are in `local`) -> the IR, with every
// diagnostic in file order and quoting its source line.
std::optional<Object> read_parsed(std::optional<frontend::PositionedJson> parsed,
                                  Diagnostics& local, std::string_view text,
                                  const std::string& file, const std::string& base_dir,
                                  const ReadOptions& opts, Diagnostics& diags) {
  Diagnostics built;
  auto obj = parsed ? build_from(&parsed->value, std::move(parsed->positions), local, file,
                                 base_dir, opts, built)
                    : build_from(nullptr, {}, local, file, base_dir, opts, built);
  built.attach_source_lines(file, text);
  for (const auto& d : built.items()) diags.add(d);
  return obj;
}

}  // namespace

std::optional<Object> read_json_text(std::string_view text, const std::string& file,
                                     const std::string& base_dir, const ReadOptions& opts,
                                     Diagnostics& diags) {
  Diagnostics local;
  return read_parsed(frontend::parse_positioned(text, file, opts.max_depth, local), local, text,
                     file, base_dir, opts, diags);
}

bool is_dsl_path(const std::string& path) {
  return path.size() >= 4 && path.compare(path.size() - 4, 4, ".efc") == 0;
}

std::optional<Object> read_spec_text(std::string_view text, const std::string& file,
                                     const std::string& base_dir, const ReadOptions& opts,
                                     Diagnostics& diags) {
  Diagnostics local;
  return read_parsed(parse_any(text, file, opts, local, nullptr), local, text, file, base_dir,
                     opts, diags);
}

std::optional<SpecDocument> read_spec_document(const std::string& path, const ReadOptions& opts,
                                               Diagnostics& diags, bool* io_error) {
  if (io_error) *io_error = false;
  auto text = read_text_file(path, diags);
  if (!text) {
    if (io_error) *io_error = true;
    return std::nullopt;
  }
  SpecDocument doc;
  Diagnostics local, built;
  auto parsed = parse_any(*text, path, opts, local, &doc.comments);
  // The shape checks need the positions; the document keeps its value.
  auto obj = parsed ? build_from(&parsed->value, parsed->positions, local, path, folder_of(path),
                                 opts, built)
                    : build_from(nullptr, {}, local, path, folder_of(path), opts, built);
  built.attach_source_lines(path, *text);
  for (const auto& d : built.items()) diags.add(d);
  if (!obj) return std::nullopt;
  doc.value = std::move(parsed->value);
  doc.text = std::move(*text);
  return doc;
}

std::optional<std::string> read_text_file(const std::string& path, Diagnostics& diags) {
  namespace fs = std::filesystem;
  auto fail = [&](const std::string& why) -> std::optional<std::string> {
    diags.error("E0001", path, 0, 0, "", "cannot read '" + path + "': " + why);
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
  return ss.str();
}

std::optional<Object> read_spec_file(const std::string& path, const ReadOptions& opts,
                                     Diagnostics& diags, bool* io_error, std::string* text_out) {
  namespace fs = std::filesystem;
  if (io_error) *io_error = false;
  auto text = read_text_file(path, diags);
  if (!text) {
    if (io_error) *io_error = true;
    return std::nullopt;
  }
  auto obj = read_spec_text(*text, path, folder_of(path), opts, diags);
  if (text_out) *text_out = std::move(*text);
  return obj;
}

std::optional<Object> read_json_file(const std::string& path, const ReadOptions& opts,
                                     Diagnostics& diags, bool* io_error) {
  return read_spec_file(path, opts, diags, io_error);
}

}  // namespace efc
