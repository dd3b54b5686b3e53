#include "cli/report.h"

#include <iostream>

namespace efc {

void Report::flush() {
  if (diags_.items().empty()) return;
  had_errors_ = had_errors_ || diags_.has_errors();
  diags_.print(std::cerr, common_.json_diagnostics);
  std::cerr.flush();
  diags_.clear();
}

void Report::note(const std::string& message) {
  diags_.note(message);
  flush();
}

int Report::fail(const std::string& code, const std::string& message, int rc, const std::string& hint) {
  diags_.error(code, "", 0, 0, "", message, hint);
  flush();
  return rc;
}

std::optional<Object> Report::load(const std::string& spec, int* rc) {
  LoadOptions opts;
  opts.allow_absolute_paths = common_.allow_absolute_paths;
  bool io_error = false;
  std::optional<Object> obj = load_spec(spec, opts, diags_, &io_error);
  flush();
  if (!obj) *rc = io_error ? kExitUsage : kExitBadInput;
  return obj;
}

}  // namespace efc
