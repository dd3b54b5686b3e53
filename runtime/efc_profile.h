// Receptor motion profiles (shared/spec/cli.md): ramp, sweep, press:N, hold:V
// (hold:lo, hold:hi), csv:FILE. Dependency-free (standard library only): the
// harness and every generated program (Bullet, ...) drive receptors with it.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace efc {

struct Profile {
  enum class Kind { Ramp, Sweep, Press, Hold, Csv };
  Kind kind = Kind::Ramp;
  int presses = 1;                                     // press:N
  enum class HoldAt { Value, Lo, Hi } hold_at = HoldAt::Value;
  double hold_value = 0;                               // hold:V
  std::string csv_path;                                // csv:FILE
  std::vector<double> csv_t;                           // strictly increasing
  std::map<std::string, std::vector<double>> csv_parts;  // column -> positions
  std::string text;                                    // as the user wrote it
};

// Parses the --profile argument. For csv:FILE also reads the file. Returns
// false with a message (and, for CSV content errors, *line set to the
// 1-based line; *io_error when the file cannot be read).
bool parse_profile(const std::string& text, Profile* out, std::string* error, int* line,
                   bool* io_error);

// Seconds over which hold:V moves from the initial position to V.
constexpr double kHoldApproach = 0.1;

// Target position of a receptor with range [lo, hi] that started at q0, at
// time t of a run lasting `duration` seconds.
double profile_target(const Profile& p, const std::string& part, double lo, double hi, double q0,
                      double t, double duration);

}  // namespace efc
