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
  // Optional, pose tracks only: per sample, the information matrix (inverse
  // covariance) of its pose error, rows and columns (rotation vector in the
  // track's frame, applied on the left; position). A registration knows it
  // (the ICP's Gauss-Newton Hessian over its noise); a file does not.
  std::vector<Eigen::Matrix<double, 6, 6>> information;
  bool has_rotations() const { return !rotations.empty(); }
  bool has_information() const { return has_rotations() && information.size() == positions.size(); }
  size_t size() const { return positions.size(); }
};

// Reads `path`. Every malformed line is a located error (E1030, file:line:col);
// false when any was found or the file cannot be read (*io_error then).
bool read_track(const std::string& path, TrackFormat format, Diagnostics& diags, Track* out,
                bool* io_error = nullptr);

}  // namespace efc::pipeline
