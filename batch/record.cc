#include "batch/record.h"

#include <sys/time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "batch/atomic_file.h"

namespace efc::batch {

using json = nlohmann::ordered_json;

nlohmann::ordered_json make_record(const Job& job, const std::vector<std::string>& command, const Outcome& o,
                                   const std::string& host) {
  std::string diagnostics = o.diagnostics.substr(0, kDiagnosticsLimit);
  const size_t total = std::max(o.diagnostics_bytes, o.diagnostics.size());
  if (total > diagnostics.size())
    diagnostics +=
        "\n[... " + std::to_string(total - diagnostics.size()) + " more bytes in logs/" + job.id + ".stderr]\n";
  json r = {{"job", job.text},  {"id", job.id},       {"line", job.line},
            {"path", job.path}, {"command", command}, {"exit_code", o.exit_code}};
  if (o.signal) r["signal"] = o.signal;
  // Milliseconds and tenths of a megabyte: what the figures can tell.
  r["seconds"] = std::round(o.seconds * 1000) / 1000;
  r["peak_rss_mb"] = std::round(o.peak_rss_mb * 10) / 10;
  r["output"] = "jobs/" + job.id;
  r["diagnostics"] = diagnostics;
  r["started"] = o.started;
  r["finished"] = o.finished;
  r["host"] = host;
  // Re-read through the serialiser so that bytes which are not UTF-8 (a
  // job's stderr may hold any) are replaced once, here.
  return json::parse(record_line(r));
}

bool record_complete(const nlohmann::ordered_json& r) {
  if (!r.is_object()) return false;
  auto is = [&](const char* k, auto pred) { return r.contains(k) && pred(r[k]); };
  const auto str = [](const json& v) { return v.is_string(); };
  const auto num = [](const json& v) { return v.is_number(); };
  const auto integer = [](const json& v) { return v.is_number_integer(); };
  return is("job", str) && is("id", str) && is("line", integer) && is("path", str) &&
         is("command", [](const json& v) { return v.is_array(); }) && is("exit_code", integer) && is("seconds", num) &&
         is("peak_rss_mb", num) && is("output", str) && is("diagnostics", str) && is("started", str) &&
         is("finished", str);
}

bool record_matches(const nlohmann::ordered_json& r, const Job& job, const std::vector<std::string>& command) {
  if (!record_complete(r)) return false;
  if (r["id"] != job.id || r["job"] != job.text || r["path"] != job.path) return false;
  return r["command"] == json(command);
}

std::optional<nlohmann::ordered_json> read_record(const std::string& path) {
  std::string text;
  if (!read_whole_file(path, &text)) return std::nullopt;
  json r = json::parse(text, nullptr, false);
  if (r.is_discarded() || !record_complete(r)) return std::nullopt;
  return r;
}

std::string record_line(const nlohmann::ordered_json& r) {
  return r.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string utc_now() {
  timeval tv{};
  gettimeofday(&tv, nullptr);
  std::tm tm{};
  gmtime_r(&tv.tv_sec, &tm);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<int>(tv.tv_usec / 1000));
  return buf;
}

}  // namespace efc::batch
