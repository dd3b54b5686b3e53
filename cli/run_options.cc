// What the commands share: loading specs, and the options play, parity and
// replay take (timing and the receptor profile).
#include "cli/commands.h"

namespace efc {

namespace {

bool check_timing(Report& report, double duration, double dt) {
  if (!(duration > 0) || duration > 1e5) {
    report.fail("E0910", "--duration must be a positive number of seconds (at most 1e5)", kExitUsage);
    return false;
  }
  if (!(dt > 0) || dt > 0.1 || dt > duration || duration / dt > 5e7) {
    report.fail("E0910",
                "--dt must be in (0, 0.1] seconds, not exceed --duration, and give at most 50 "
                "million steps",
                kExitUsage);
    return false;
  }
  return true;
}

// 0, or the exit code after reporting why --profile is unusable.
int parse_profile_option(Report& report, const std::string& text, Profile* profile) {
  std::string error;
  int line = 0;
  bool io = false;
  if (parse_profile(text, profile, &error, &line, &io)) return kExitOk;
  if (io) {
    report.diags().error("E0001", profile->csv_path.empty() ? text : profile->csv_path, 0, 0, "", error);
    report.flush();
    return kExitUsage;
  }
  if (line > 0) {  // a csv:FILE profile whose content is wrong: located in it
    report.diags().error("E0903", text.substr(4), line, 1, "", error);
    report.flush();
    return kExitBadInput;
  }
  return report.fail("E0910", error, kExitUsage);
}

}  // namespace

std::optional<Object> load_for_run(Report& report, const std::string& spec, const std::string& profile_text,
                                   double duration, double dt, Profile* profile, int* rc) {
  if (!check_timing(report, duration, dt)) {
    *rc = kExitUsage;
    return std::nullopt;
  }
  if ((*rc = parse_profile_option(report, profile_text, profile))) return std::nullopt;
  return report.load(spec, rc);
}

std::vector<Object> load_all(Report& report, const std::vector<std::string>& specs, int* rc) {
  std::vector<Object> objects;
  *rc = kExitOk;
  for (const std::string& spec : specs) {
    int load_rc = kExitOk;
    std::optional<Object> obj = report.load(spec, &load_rc);
    if (obj)
      objects.push_back(std::move(*obj));
    else
      *rc = std::max(*rc, load_rc);
  }
  return objects;
}

}  // namespace efc
