// efc fmt (canonical formatting) and efc convert (.json <-> .efc).
//
// Both read a document with the shape checks of `efc check` (syntax, types,
// keys, names) but not the cross-field rules, so a spec that is still being
// written can be formatted. Output is written to a temporary file and renamed
// over the target, so a failure never leaves a half-written file.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "compiler/driver/commands.h"
#include "compiler/frontend/dsl.h"
#include "compiler/frontend/json_reader.h"
#include "compiler/frontend/positioned_json.h"
#include "compiler/frontend/spec_builder.h"

namespace efc {
namespace {

namespace fs = std::filesystem;

struct Document {
  nlohmann::json value;
  dsl::CommentMap comments;
};

// Reads `path` (either format) and runs the shape checks. Errors go to diags;
// *io_error is set when the file cannot be read.
std::optional<Document> read_document(const std::string& path, const CommonOptions& common,
                                      Diagnostics& diags, bool* io_error) {
  *io_error = false;
  auto text = read_text_file(path, diags);
  if (!text) {
    *io_error = true;
    return std::nullopt;
  }
  ReadOptions opts;
  opts.allow_absolute_paths = common.allow_absolute_paths;
  Diagnostics local;
  Document doc;
  std::optional<frontend::PositionedJson> parsed =
      is_dsl_path(path)
          ? dsl::parse_with_comments(*text, path, opts.max_depth, local, &doc.comments)
          : frontend::parse_positioned(*text, path, opts.max_depth, local);
  if (parsed) {
    Object obj;
    obj.file = path;
    std::string base = fs::path(path).parent_path().string();
    obj.base_dir = base.empty() ? "." : base;
    obj.positions = parsed->positions;
    frontend::build_object(parsed->value, obj, opts, local);
    doc.value = std::move(parsed->value);
  }
  if (is_dsl_path(path)) local.attach_source_lines(path, *text);
  std::vector<Diagnostic> items = local.items();
  std::stable_sort(items.begin(), items.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::make_pair(a.line, a.col) < std::make_pair(b.line, b.col);
  });
  for (auto& d : items) diags.add(std::move(d));
  if (!parsed || local.has_errors()) return std::nullopt;
  return doc;
}

bool is_json_path(const std::string& path) {
  return path.size() >= 5 && path.compare(path.size() - 5, 5, ".json") == 0;
}

// Writes `text` to `path` through a temporary file in the same folder.
bool write_atomically(const std::string& path, const std::string& text, std::string* error) {
  const fs::path target(path);
  fs::path tmp = target;
  tmp += ".efc-tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      *error = "cannot write '" + path + "'";
      return false;
    }
    out << text;
    out.close();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      *error = "cannot write '" + path + "'";
      return false;
    }
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    *error = "cannot write '" + path + "': " + ec.message();
    return false;
  }
  return true;
}

std::string render(const Document& doc, bool dsl) {
  return dsl ? dsl::print(doc.value, &doc.comments) : dsl::print_json(doc.value);
}

}  // namespace

int cmd_fmt(const std::vector<std::string>& files, bool check_only, const CommonOptions& common) {
  int rc = 0;
  for (const std::string& file : files) {
    Diagnostics diags;
    if (!is_dsl_path(file) && !is_json_path(file)) {
      std::cerr << "efc fmt: '" << file << "' is neither .efc nor .json\n";
      rc = std::max(rc, 2);
      continue;
    }
    bool io_error = false;
    auto doc = read_document(file, common, diags, &io_error);
    diags.print(std::cerr, common.json_diagnostics);
    if (!doc) {
      rc = std::max(rc, io_error ? 2 : 1);
      continue;
    }
    const std::string formatted = render(*doc, is_dsl_path(file));
    Diagnostics dummy;
    const std::string current = read_text_file(file, dummy).value_or("");
    if (formatted == current) continue;
    if (check_only) {
      std::cerr << file << ": would be reformatted\n";
      rc = std::max(rc, 1);
      continue;
    }
    std::string error;
    if (!write_atomically(file, formatted, &error)) {
      std::cerr << "efc fmt: " << error << "\n";
      rc = std::max(rc, 2);
      continue;
    }
    std::cerr << file << ": formatted\n";
  }
  return rc;
}

int cmd_convert(const std::string& in, const std::string& out, const CommonOptions& common) {
  const bool out_dsl = is_dsl_path(out);
  if ((!is_dsl_path(in) && !is_json_path(in)) || (!out_dsl && !is_json_path(out))) {
    std::cerr << "efc convert: files must end in .json or .efc (got '" << in << "' -> '" << out
              << "')\n";
    return 2;
  }
  Diagnostics diags;
  bool io_error = false;
  auto doc = read_document(in, common, diags, &io_error);
  diags.print(std::cerr, common.json_diagnostics);
  if (!doc) return io_error ? 2 : 1;
  if (!out_dsl && !doc->comments.empty())
    std::cerr << "efc convert: warning: " << doc->comments.size()
              << " comment(s) are not carried into JSON (it has no comments)\n";
  // Relative mesh paths resolve against the spec's folder: moving the spec
  // to another folder breaks them, so say so.
  std::error_code ec;
  const fs::path in_dir = fs::absolute(fs::path(in).parent_path(), ec);
  const fs::path out_dir = fs::absolute(fs::path(out).parent_path(), ec);
  if (in_dir.lexically_normal() != out_dir.lexically_normal() &&
      doc->value.dump().find("\"mesh\"") != std::string::npos)
    std::cerr << "efc convert: warning: mesh paths are relative to '" << in_dir.string()
              << "'; they were not rewritten for '" << out_dir.string() << "'\n";
  std::string error;
  if (!write_atomically(out, render(*doc, out_dsl), &error)) {
    std::cerr << "efc convert: " << error << "\n";
    return 2;
  }
  return 0;
}

}  // namespace efc
