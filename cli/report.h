// Everything a command tells the user goes through one Report: spec
// diagnostics, the program's own errors and progress notes, in compiler
// style or, with --diagnostics-format json, as JSON lines and nothing else.
// Messages are printed as they happen (a long command shows its progress),
// in the order they were made.
#pragma once

#include <optional>
#include <string>

#include "compiler/core/load.h"
#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc {

// Exit codes (shared/spec/cli.md).
constexpr int kExitOk = 0;
constexpr int kExitBadInput = 1;
constexpr int kExitUsage = 2;  // also: a file that cannot be read or written

struct CommonOptions {
  bool json_diagnostics = false;  // --diagnostics-format json
  bool allow_absolute_paths = false;
};

class Report {
 public:
  explicit Report(const CommonOptions& common) : common_(common) {}
  ~Report() { flush(); }
  Report(const Report&) = delete;
  Report& operator=(const Report&) = delete;

  // Where commands and libraries add diagnostics; flush() prints them.
  Diagnostics& diags() { return diags_; }
  const CommonOptions& options() const { return common_; }
  // Prints what was added since the last flush, then forgets it.
  void flush();

  // A progress line (printed at once).
  void note(const std::string& message);
  // The program's own error (no spec location): prints it and returns `rc`.
  int fail(const std::string& code, const std::string& message, int rc, const std::string& hint = "");
  // The exit code for what was reported: kExitBadInput after errors, else 0.
  int exit_code() const { return had_errors_ ? kExitBadInput : kExitOk; }

  // Reads, resolves and checks a spec, reporting every problem. nullopt on
  // failure, with *rc = 2 when the file could not be read, else 1.
  std::optional<Object> load(const std::string& spec, int* rc);

 private:
  CommonOptions common_;
  Diagnostics diags_;
  bool had_errors_ = false;
};

}  // namespace efc
