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

namespace efc {
namespace {

namespace fs = std::filesystem;

// Reads `path` (either format) with the shape checks; errors go to diags.
std::optional<SpecDocument> read_document(const std::string& path, const CommonOptions& common,
                                          Diagnostics& diags, bool* io_error) {
  ReadOptions opts;
  opts.allow_absolute_paths = common.allow_absolute_paths;
  return read_spec_document(path, opts, diags, io_error);
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

std::string render(const SpecDocument& doc, bool dsl) {
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
    if (formatted == doc->text) continue;
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
