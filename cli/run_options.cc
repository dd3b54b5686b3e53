// The options play and parity share: timing and the receptor profile.
#include "cli/commands.h"

namespace efc {

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

}  // namespace efc
