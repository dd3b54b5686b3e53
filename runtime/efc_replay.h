// Replay of function templates with no simulator: every joint is ideal (a
// profile joint is exactly at its profile target, a geometry effect's effector
// exactly at the effect's output). It is the reference the Python runtime
// (backends/python/efc_templates.py, `--csv`) is compared with byte for byte,
// so both sides must keep the same order of operations (README there:
// "Replay semantics"). Dependency-free: standard library and the runtime.
#ifndef EFC_REPLAY_H_
#define EFC_REPLAY_H_

#include <string>
#include <vector>

#include "efc_profile.h"
#include "efc_runtime.h"

namespace efc {

struct ReplayJoint {
  std::string name;        // the part's name: what a csv:FILE profile's column names
  double lo, hi;           // the range profiles use (continuous: 0 and 2 pi)
  double initial;          // position before t = 0, and the profile's q0
  bool profile_driven;     // drive_by == "profile"
};

struct ReplayFunction {
  std::string name;        // column prefix: name.s_R, name.s_E, name.measured
  efc_rt::FunctionParams params;
  int receptor_joint;      // index into the joints
  int effector_joint;      // index into the joints; -1 unless the effect is geometry
};

struct ReplayLog {
  std::vector<std::string> columns;       // t, then F.s_R, F.s_E, F.measured per function
  std::vector<std::vector<double>> rows;  // one per step k = 0..round(duration / dt)
};

// Runs the templates in table order over `profile` for `duration` seconds at
// step dt; measured = the effect's output. Indices must be valid (the caller
// built them from a checked table).
ReplayLog replay_templates(const std::vector<ReplayJoint>& joints,
                           const std::vector<ReplayFunction>& functions, const Profile& profile,
                           double duration, double dt);

// The log as CSV text, "%.9g" and "\n": exactly what efc_templates.py writes.
std::string replay_csv(const ReplayLog& log);

}  // namespace efc

#endif  // EFC_REPLAY_H_
