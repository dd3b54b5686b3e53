// efc convert IN -o OUT: between JSON and the DSL, by extension; lossless
// (but JSON has no comments).
#include <filesystem>

#include "cli/commands.h"
#include "cli/spec_text.h"

namespace efc {

namespace fs = std::filesystem;

int cmd_convert(Report& report, const std::string& in, const std::string& out) {
  const bool out_dsl = is_dsl_path(out);
  if ((!is_dsl_path(in) && !is_json_path(in)) || (!out_dsl && !is_json_path(out)))
    return report.fail("E0910", "files must end in .json or .efc (got '" + in + "' -> '" + out + "')",
                       kExitUsage);
  int rc = kExitOk;
  auto doc = read_document_reported(report, in, &rc);
  if (!doc) return rc;
  if (!out_dsl && !doc->comments.empty())
    report.diags().warning("W0910", in, 0, 0, "",
                           std::to_string(doc->comments.size()) +
                               " comment(s) are not carried into JSON (it has no comments)");
  // Relative mesh paths resolve against the spec's folder: moving the spec
  // to another folder breaks them, so say so.
  std::error_code ec;
  const fs::path in_dir = fs::absolute(fs::path(in).parent_path(), ec);
  const fs::path out_dir = fs::absolute(fs::path(out).parent_path(), ec);
  if (in_dir.lexically_normal() != out_dir.lexically_normal() &&
      doc->value.dump().find("\"mesh\"") != std::string::npos)
    report.diags().warning("W0910", in, 0, 0, "",
                           "mesh paths are relative to '" + in_dir.string() +
                               "'; they were not rewritten for '" + out_dir.string() + "'");
  report.flush();
  std::string error;
  if (!write_atomically(out, render_document(*doc, out_dsl), &error))
    return report.fail("E0900", error, kExitUsage);
  return kExitOk;
}

}  // namespace efc
