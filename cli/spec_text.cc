#include "cli/spec_text.h"

#include <filesystem>
#include <fstream>

namespace efc {

namespace fs = std::filesystem;

bool is_json_path(const std::string& path) {
  return path.size() >= 5 && path.compare(path.size() - 5, 5, ".json") == 0;
}

std::optional<SpecDocument> read_document_reported(Report& report, const std::string& path, int* rc) {
  ReadOptions opts;
  opts.allow_absolute_paths = report.options().allow_absolute_paths;
  bool io_error = false;
  std::optional<SpecDocument> doc = read_spec_document(path, opts, report.diags(), &io_error);
  report.flush();
  if (!doc) *rc = io_error ? kExitUsage : kExitBadInput;
  return doc;
}

std::string render_document(const SpecDocument& doc, bool dsl) {
  return dsl ? dsl::print(doc.value, &doc.comments) : dsl::print_json(doc.value);
}

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

}  // namespace efc
