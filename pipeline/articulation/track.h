// A motion track of one moving thing: positions (a hand or a handle) and,
// for 6-DoF tracks, orientations (a part's or a marker's pose). The input
// of the articulation estimator (`efc articulate`, and later `efc infer`'s
// part and hand motion).
//
// Formats (--format), one sample per line, '#' lines and blank lines skipped:
//   xyz    x y z            (more columns are ignored), or t x y z when the
//                           line has exactly four (hands.txt); a sample with
//                           nan (no hand seen) is skipped
//   pose7  x y z qx qy qz qw (more columns are ignored: the TUM articulation
//                           data's marker size)
//   tum    t x y z qx qy qz qw (poses.txt)
#pragma once

#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "compiler/diagnostics.h"

namespace efc::pipeline {

enum class TrackFormat { Xyz, Pose7, Tum };
// "xyz", "pose7", "tum"; false otherwise.
bool parse_track_format(const std::string& text, TrackFormat* out);

struct Track {
  std::vector<Eigen::Vector3d> positions;
  std::vector<Eigen::Quaterniond> rotations;  // empty for xyz tracks
  bool has_rotations() const { return !rotations.empty(); }
  size_t size() const { return positions.size(); }
};

// Reads `path`. Every malformed line is a located error (E1030, file:line:col);
// false when any was found or the file cannot be read (*io_error then).
bool read_track(const std::string& path, TrackFormat format, Diagnostics& diags, Track* out,
                bool* io_error = nullptr);

}  // namespace efc::pipeline
