// See efc_replay.h. Bit-identity with the Python mirror also needs the
// compiler to keep every a + b * c as two roundings: no -ffast-math, and no
// FMA contraction (x86-64 without -march that enables FMA contracts nothing).
#include "efc_replay.h"

#include <cmath>
#include <cstdio>

namespace efc {
namespace {

void drive_profile_joints(const std::vector<ReplayJoint>& joints, const Profile& profile,
                          double t, double duration, std::vector<double>* positions) {
  for (size_t j = 0; j < joints.size(); ++j) {
    const ReplayJoint& joint = joints[j];
    if (joint.profile_driven)
      (*positions)[j] = profile_target(profile, joint.name, joint.lo, joint.hi, joint.initial, t,
                                       duration);
  }
}

std::vector<std::string> log_columns(const std::vector<ReplayFunction>& functions) {
  std::vector<std::string> columns{"t"};
  for (const ReplayFunction& f : functions) {
    columns.push_back(f.name + ".s_R");
    columns.push_back(f.name + ".s_E");
    columns.push_back(f.name + ".measured");
  }
  return columns;
}

}  // namespace

ReplayLog replay_templates(const std::vector<ReplayJoint>& joints,
                           const std::vector<ReplayFunction>& functions, const Profile& profile,
                           double duration, double dt) {
  std::vector<double> positions(joints.size());
  for (size_t j = 0; j < joints.size(); ++j) positions[j] = joints[j].initial;
  // The profile holds at t = 0 already, so reset sees the same receptors as step 0.
  drive_profile_joints(joints, profile, 0.0, duration, &positions);
  std::vector<efc_rt::FunctionState> states(functions.size());
  for (size_t i = 0; i < functions.size(); ++i)
    efc_rt::function_init(functions[i].params, positions[functions[i].receptor_joint], &states[i]);

  ReplayLog log;
  log.columns = log_columns(functions);
  const long steps = std::lround(duration / dt);
  log.rows.reserve(static_cast<size_t>(steps) + 1);
  for (long k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) * dt;  // the exact grid, as efc play
    drive_profile_joints(joints, profile, t, duration, &positions);
    std::vector<double> row;
    row.reserve(1 + 3 * functions.size());
    row.push_back(t);
    for (size_t i = 0; i < functions.size(); ++i) {
      const ReplayFunction& f = functions[i];
      const double s_R = positions[f.receptor_joint];
      efc_rt::function_step(f.params, s_R, dt, &states[i]);
      const double output = states[i].effect.output;
      // An ideal servo: a later function in a chain sees the new position in this step.
      if (f.params.effect.kind == efc_rt::kGeometry && f.effector_joint >= 0)
        positions[f.effector_joint] = output;
      row.insert(row.end(), {s_R, states[i].mapping.s_E, output});
    }
    log.rows.push_back(std::move(row));
  }
  return log;
}

std::string replay_csv(const ReplayLog& log) {
  std::string text;
  for (size_t i = 0; i < log.columns.size(); ++i) text += (i ? "," : "") + log.columns[i];
  text += "\n";
  char cell[32];
  for (const std::vector<double>& row : log.rows) {
    for (size_t i = 0; i < row.size(); ++i) {
      std::snprintf(cell, sizeof cell, "%.9g", row[i]);
      if (i) text += ',';
      text += cell;
    }
    text += "\n";
  }
  return text;
}

}  // namespace efc
