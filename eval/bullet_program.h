// Building and running the generated Bullet program, for parity checks: the
// Bullet target is emitted, configured and compiled with cmake once per
// distinct output (cached under $TMPDIR/efc-parity-cache), then run.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc {

using ProgressFn = std::function<void(const std::string&)>;

// Returns the built program's path, or "" after adding an E0913 (build) or
// E0900 (I/O) error to diags. `progress` hears what it is doing.
std::string build_bullet_program(const Object& obj, Diagnostics& diags, const ProgressFn& progress);

// Runs `exe` following the receptor trajectory in `trajectory_csv` (a csv:
// profile) for `duration` at `dt`, full precision. Fills the CSV's header and
// rows; false after adding an E0913 error (with the program's stderr tail).
bool run_bullet_program(const std::string& exe, const std::string& trajectory_csv, double duration,
                        double dt, const std::string& work_dir, Diagnostics& diags,
                        std::vector<std::string>* header, std::vector<std::vector<double>>* rows,
                        double* steps_per_second);

// Reads a numeric CSV with a header line.
bool read_numeric_csv(const std::string& path, std::vector<std::string>* header,
                      std::vector<std::vector<double>>* rows);

}  // namespace efc
