// Parity between two simulators (a metric): the MuJoCo harness's log and the
// Bullet program's CSV over the same receptor trajectory, compared per
// function.
//
// The same trajectory: the harness's receptors follow the profile through a
// servo (they lag it slightly), so the Bullet program is given the positions
// the harness realised and prescribes them kinematically. s_E is then a
// function of identical inputs for every function whose receptor the profile
// moves, and must agree to float tolerance (kSETolerance relative) on every
// row. A chained function's receptor is a geometry effector that each
// simulator moves with its own dynamics; its s_E must agree on every row where
// both simulators' s_E have held for kSteadyHold, and switch the same number
// of times, each switch at most kChainShift away from the harness's.
// Geometry effects: on rows where s_E has held for kSteadyHold, the two
// measured joint positions differ by at most kGeometryTolerance of the
// effect's range.
#pragma once

#include <string>
#include <vector>

#include "compiler/ir.h"

namespace efc {

constexpr double kSETolerance = 1e-9;         // relative
constexpr double kSteadyHold = 0.5;           // s
constexpr double kGeometryTolerance = 0.02;   // of the effect's range
constexpr double kChainShift = 0.05;          // s: the most a chained switch may move

// A log: columns t, then F.s_R, F.s_E, F.measured per function; one row per step.
struct SimLog {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
};

struct FunctionParity {
  std::string function;
  EffectType effect = EffectType::Geometry;
  bool chained = false;          // its receptor is another function's geometry effector
  double max_ds_r = 0, max_ds_e = 0, max_dmeasured = 0;
  double steady_fraction = -1;   // geometry: worst steady |d measured| / range (else -1)
  bool se_ok = true, measured_ok = true;
  std::string note;              // chained: switch counts or the largest shift
  bool ok() const { return se_ok && measured_ok; }
};

// Compares `reference` (the harness) with `other` (same columns and rows).
// Empty with *error set when their shapes differ.
std::vector<FunctionParity> compare_logs(const Object& obj, const SimLog& reference,
                                         const SimLog& other, double dt, std::string* error);

}  // namespace efc
