#include "efc_profile.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace efc {
namespace {

bool parse_double(const std::string& s, double* v) {
  if (s.empty()) return false;
  errno = 0;
  char* end = nullptr;
  *v = std::strtod(s.c_str(), &end);
  return errno == 0 && end == s.c_str() + s.size() && std::isfinite(*v);
}

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) cells.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') cells.push_back("");
  return cells;
}

bool read_csv(Profile* p, std::string* error, int* line, bool* io_error) {
  std::ifstream in(p->csv_path);
  if (!in) {
    *io_error = true;
    *error = "cannot read profile file '" + p->csv_path + "'";
    return false;
  }
  std::string text;
  std::vector<std::string> header;
  int n = 0;
  while (std::getline(in, text)) {
    ++n;
    if (trim(text).empty()) continue;
    std::vector<std::string> cells = split(text);
    if (header.empty()) {
      header = cells;
      if (header[0] != "t" || header.size() < 2) {
        *line = n;
        *error = "profile CSV must start with a header 't,<part>[,<part>...]'";
        return false;
      }
      for (size_t i = 1; i < header.size(); ++i) p->csv_parts[header[i]];
      if (p->csv_parts.size() != header.size() - 1) {
        *line = n;
        *error = "profile CSV names a column twice";
        return false;
      }
      continue;
    }
    if (cells.size() != header.size()) {
      *line = n;
      *error = "expected " + std::to_string(header.size()) + " values, found " +
               std::to_string(cells.size());
      return false;
    }
    double t;
    if (!parse_double(cells[0], &t)) {
      *line = n;
      *error = "time '" + cells[0] + "' is not a finite number";
      return false;
    }
    if (!p->csv_t.empty() && t <= p->csv_t.back()) {
      *line = n;
      *error = "times must increase strictly";
      return false;
    }
    p->csv_t.push_back(t);
    for (size_t i = 1; i < cells.size(); ++i) {
      double v;
      if (!parse_double(cells[i], &v)) {
        *line = n;
        *error = "value '" + cells[i] + "' of column '" + header[i] + "' is not a finite number";
        return false;
      }
      p->csv_parts[header[i]].push_back(v);
    }
  }
  if (p->csv_t.empty()) {
    *line = n;
    *error = header.empty() ? "profile CSV is empty" : "profile CSV has no data rows";
    return false;
  }
  return true;
}

double interpolate(const std::vector<double>& ts, const std::vector<double>& vs, double t) {
  if (t <= ts.front()) return vs.front();
  if (t >= ts.back()) return vs.back();
  const size_t i = std::upper_bound(ts.begin(), ts.end(), t) - ts.begin();
  const double u = (t - ts[i - 1]) / (ts[i] - ts[i - 1]);
  return vs[i - 1] + u * (vs[i] - vs[i - 1]);
}

}  // namespace

bool parse_profile(const std::string& text, Profile* out, std::string* error, int* line,
                   bool* io_error) {
  *line = 0;
  *io_error = false;
  Profile p;
  p.text = text;
  const size_t colon = text.find(':');
  const std::string head = text.substr(0, colon);
  const std::string arg = colon == std::string::npos ? "" : text.substr(colon + 1);
  if (text == "ramp") {
    p.kind = Profile::Kind::Ramp;
  } else if (text == "sweep") {
    p.kind = Profile::Kind::Sweep;
  } else if (head == "press" && colon != std::string::npos) {
    p.kind = Profile::Kind::Press;
    double n;
    if (!parse_double(arg, &n) || n < 1 || n != std::floor(n) || n > 1e6) {
      *error = "press:N needs a whole number of presses >= 1, got '" + arg + "'";
      return false;
    }
    p.presses = static_cast<int>(n);
  } else if (head == "hold" && colon != std::string::npos) {
    p.kind = Profile::Kind::Hold;
    if (arg == "lo") {
      p.hold_at = Profile::HoldAt::Lo;
    } else if (arg == "hi") {
      p.hold_at = Profile::HoldAt::Hi;
    } else if (!parse_double(arg, &p.hold_value)) {
      *error = "hold:V needs a finite number, 'lo' or 'hi', got '" + arg + "'";
      return false;
    }
  } else if (head == "csv" && colon != std::string::npos && !arg.empty()) {
    p.kind = Profile::Kind::Csv;
    p.csv_path = arg;
    if (!read_csv(&p, error, line, io_error)) return false;
  } else {
    *error = "unknown profile '" + text + "' (expected ramp, sweep, press:N, hold:V, csv:FILE)";
    return false;
  }
  *out = std::move(p);
  return true;
}

double profile_target(const Profile& p, const std::string& part, double lo, double hi, double q0,
                      double t, double duration) {
  const double u = duration > 0 ? std::clamp(t / duration, 0.0, 1.0) : 1.0;
  switch (p.kind) {
    case Profile::Kind::Ramp:
      return lo + (hi - lo) * u;
    case Profile::Kind::Sweep:
      return u < 0.5 ? lo + (hi - lo) * 2 * u : hi - (hi - lo) * (2 * u - 1);
    case Profile::Kind::Press: {
      // Each cycle: rest at lo, rise to hi, dwell, return to lo, rest. The
      // rests let a sprung receptor settle, so every press is a clean edge.
      const double cycle = u * p.presses;
      const double c = cycle - std::floor(cycle);
      double a;  // 0 = lo, 1 = hi
      if (c < 0.2) a = 0;
      else if (c < 0.4) a = (c - 0.2) / 0.2;
      else if (c < 0.6) a = 1;
      else if (c < 0.8) a = 1 - (c - 0.6) / 0.2;
      else a = 0;
      if (u >= 1.0) a = 0;
      return lo + (hi - lo) * a;
    }
    case Profile::Kind::Hold: {
      double v = p.hold_at == Profile::HoldAt::Lo   ? lo
                 : p.hold_at == Profile::HoldAt::Hi ? hi
                                                    : p.hold_value;
      if (t >= kHoldApproach) return v;
      return q0 + (v - q0) * (t / kHoldApproach);
    }
    case Profile::Kind::Csv: {
      auto it = p.csv_parts.find(part);
      if (it == p.csv_parts.end()) return q0;
      return interpolate(p.csv_t, it->second, t);
    }
  }
  return q0;
}

}  // namespace efc
