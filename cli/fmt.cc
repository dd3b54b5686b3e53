// efc fmt FILE... [--check]: rewrite specs in canonical form (comments kept);
// --check changes nothing and exits 1 if a file would change.
#include "cli/commands.h"
#include "cli/spec_text.h"

namespace efc {

int cmd_fmt(Report& report, const std::vector<std::string>& files, bool check_only) {
  int rc = kExitOk;
  for (const std::string& file : files) {
    if (!is_dsl_path(file) && !is_json_path(file)) {
      rc = std::max(rc, report.fail("E0910", "'" + file + "' is neither .efc nor .json", kExitUsage));
      continue;
    }
    int read_rc = kExitOk;
    auto doc = read_document_reported(report, file, &read_rc);
    if (!doc) {
      rc = std::max(rc, read_rc);
      continue;
    }
    const std::string formatted = render_document(*doc, is_dsl_path(file));
    if (formatted == doc->text) continue;
    if (check_only) {
      report.note(file + ": would be reformatted");
      rc = std::max(rc, kExitBadInput);
      continue;
    }
    std::string error;
    if (!write_atomically(file, formatted, &error)) {
      rc = std::max(rc, report.fail("E0900", error, kExitUsage));
      continue;
    }
    report.note(file + ": formatted");
  }
  return rc;
}

}  // namespace efc
