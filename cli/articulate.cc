// efc articulate --track FILE --format xyz|pose7|tum: which joint moved a
// track (pipeline/articulation), as one JSON object on stdout.
#include <iostream>

#include "cli/commands.h"
#include "pipeline/articulation/articulation.h"

namespace efc {

int cmd_articulate(Report& report, const std::string& track_path, const std::string& format_text) {
  pipeline::TrackFormat format;
  if (!pipeline::parse_track_format(format_text, &format))
    return report.fail("E0910", "--format must be xyz, pose7 or tum (not '" + format_text + "')", kExitUsage);
  pipeline::Track track;
  bool io_error = false;
  if (!pipeline::read_track(track_path, format, report.diags(), &track, &io_error)) {
    report.flush();
    return io_error ? kExitUsage : kExitBadInput;
  }
  report.flush();
  std::cout << pipeline::articulation_json(pipeline::estimate_articulation(track)) << "\n";
  return kExitOk;
}

}  // namespace efc
