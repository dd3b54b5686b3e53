// One job's result record: DIR/records/ID.json, and one line of the results
// files. Written once, atomically, when the job has ended; a job without a
// complete record is run (again) by the next `efc batch` over the same DIR.
//   {"job": the manifest line, "id", "line", "path", "command": [...],
//    "exit_code", "signal" (only when killed by one), "seconds",
//    "peak_rss_mb", "output": "jobs/ID" (relative to DIR),
//    "diagnostics": its stderr (the first 16 KiB), "started", "finished"
//    (UTC, ISO 8601), "host"}
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "batch/manifest.h"

namespace efc::batch {

struct Outcome {
  int exit_code = 0;   // the job's exit status, or 128 + the signal that killed it
  int signal = 0;      // that signal, or 0
  double seconds = 0;  // wall time from start to end
  double peak_rss_mb = 0;
  std::string started, finished;  // ISO 8601 UTC
  std::string diagnostics;        // its stderr (the first kDiagnosticsLimit bytes of it)
  size_t diagnostics_bytes = 0;   // how long its stderr was
};

// Bytes of a job's stderr kept in its record (the whole is in logs/ID.stderr).
constexpr size_t kDiagnosticsLimit = 16 * 1024;

nlohmann::ordered_json make_record(const Job& job, const std::vector<std::string>& command, const Outcome& outcome,
                                   const std::string& host);

// Whether `r` is a whole record (every field, of the right type).
bool record_complete(const nlohmann::ordered_json& r);

// Whether a complete record is this job's under this command (the line and
// the command unchanged): only then is the job skipped on a re-run.
bool record_matches(const nlohmann::ordered_json& r, const Job& job, const std::vector<std::string>& command);

// The record in `path`, if it is there, parses and is complete.
std::optional<nlohmann::ordered_json> read_record(const std::string& path);

// One line of a results file (no newline); invalid UTF-8 replaced.
std::string record_line(const nlohmann::ordered_json& r);

// Now, as "2026-01-31T12:34:56.789Z".
std::string utc_now();

}  // namespace efc::batch
