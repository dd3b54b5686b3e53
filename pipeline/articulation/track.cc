#include "pipeline/articulation/track.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace efc::pipeline {
namespace {

// The numbers of one line with the column each starts at; false at the
// first token that is not a number (*bad_col says where).
bool split_numbers(const std::string& line, std::vector<double>* values, std::vector<int>* cols,
                   int* bad_col, std::string* bad_token) {
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == ',' || line[i] == '\r')) ++i;
    if (i >= line.size()) break;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != ',' && line[j] != '\r') ++j;
    const std::string token = line.substr(i, j - i);
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size()) {
      *bad_col = static_cast<int>(i) + 1;
      *bad_token = token;
      return false;
    }
    values->push_back(v);
    cols->push_back(static_cast<int>(i) + 1);
    i = j;
  }
  return true;
}

}  // namespace

bool parse_track_format(const std::string& text, TrackFormat* out) {
  if (text == "xyz") *out = TrackFormat::Xyz;
  else if (text == "pose7") *out = TrackFormat::Pose7;
  else if (text == "tum") *out = TrackFormat::Tum;
  else return false;
  return true;
}

bool read_track(const std::string& path, TrackFormat format, Diagnostics& diags, Track* out, bool* io_error) {
  std::ifstream in(path);
  if (!in) {
    if (io_error) *io_error = true;
    diags.error("E0001", path, 0, 0, "", "cannot read the track file");
    return false;
  }
  const size_t errors_before = diags.error_count();
  const size_t need = format == TrackFormat::Xyz ? 3 : (format == TrackFormat::Pose7 ? 7 : 8);
  const char* shape = format == TrackFormat::Xyz ? "x y z (or t x y z)"
                      : format == TrackFormat::Pose7 ? "x y z qx qy qz qw"
                                                     : "t x y z qx qy qz qw";
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::vector<double> v;
    std::vector<int> col;
    int bad_col = 0;
    std::string bad;
    if (!split_numbers(line, &v, &col, &bad_col, &bad)) {
      diags.error("E1030", path, number, bad_col, "", "'" + bad + "' is not a number", std::string("a line is ") + shape);
      continue;
    }
    if (v.size() < need || (format == TrackFormat::Tum && v.size() != 8)) {
      diags.error("E1030", path, number, 1, "",
                  std::to_string(v.size()) + " numbers; a line is " + shape);
      continue;
    }
    // xyz with exactly four columns is hands.txt: t x y z.
    const size_t p0 = format == TrackFormat::Tum || (format == TrackFormat::Xyz && v.size() == 4) ? 1 : 0;
    const Eigen::Vector3d p(v[p0], v[p0 + 1], v[p0 + 2]);
    if (format == TrackFormat::Xyz && p.array().isNaN().all()) continue;  // no hand seen
    bool finite = true;
    for (size_t k = 0; k < v.size() && k < p0 + (format == TrackFormat::Xyz ? 3 : 7); ++k)
      if (!std::isfinite(v[k])) {
        diags.error("E1030", path, number, col[k], "", "not a finite number");
        finite = false;
        break;
      }
    if (!finite) continue;
    out->positions.push_back(p);
    if (format != TrackFormat::Xyz) {
      Eigen::Quaterniond q(v[p0 + 6], v[p0 + 3], v[p0 + 4], v[p0 + 5]);
      if (q.norm() < 1e-6) {
        diags.error("E1030", path, number, col[p0 + 3], "", "the quaternion is zero");
        continue;
      }
      out->rotations.push_back(q.normalized());
    }
  }
  if (diags.error_count() != errors_before) return false;
  if (out->size() < 3) {
    diags.error("E1031", path, 0, 0, "",
                "the track has " + std::to_string(out->size()) + " samples; at least 3 are needed to tell a joint",
                "record more of the motion");
    return false;
  }
  return true;
}

}  // namespace efc::pipeline
