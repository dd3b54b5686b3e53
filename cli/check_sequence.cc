// efc check-sequence SEQ...: validate recording folders against
// shared/spec/sequence.md; every problem located, a summary note per good one.
#include <algorithm>
#include <filesystem>

#include "cli/commands.h"
#include "sequence/sequence.h"

namespace efc {
namespace {

// "SEQ: ok, 300 frames 640x480, depth, masks: hand, handle, poses, hands, truth"
std::string summary(const seq::Sequence& s) {
  const seq::Meta& m = s.meta();
  std::string out = s.dir() + ": ok, " + std::to_string(m.frames) + " frames " + std::to_string(m.width) +
                    "x" + std::to_string(m.height);
  if (s.has_depth()) out += ", depth";
  if (!s.mask_names().empty()) {
    out += ", masks:";
    for (size_t i = 0; i < s.mask_names().size(); ++i) out += (i ? ", " : " ") + s.mask_names()[i];
  }
  if (s.has_poses()) out += ", poses";
  if (s.has_hands()) out += ", hands";
  if (s.has_truth()) out += ", truth";
  return out;
}

}  // namespace

int cmd_check_sequence(Report& report, const std::vector<std::string>& dirs) {
  int rc = kExitOk;
  for (const std::string& dir : dirs) {
    // A path that is no folder at all cannot be read (exit 2, as for an
    // unreadable spec); a folder that is not a valid sequence is bad input (1).
    std::error_code ec;
    const bool is_folder = std::filesystem::is_directory(dir, ec);
    seq::Sequence s;
    const bool ok = s.open(dir, report.diags()) && s.check_all(report.diags());
    report.flush();
    if (ok)
      report.note(summary(s));
    else
      rc = std::max(rc, is_folder ? kExitBadInput : kExitUsage);
  }
  return rc;
}

}  // namespace efc
