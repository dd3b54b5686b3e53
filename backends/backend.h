// One small interface for every target, registered in one table (registry.cc).
// A backend reads a resolved, checked IR and writes files; it never
// re-validates. A feature it cannot express becomes a warning naming the
// feature and what was emitted instead, never a silent drop.
#pragma once

#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc {

class Backend {
 public:
  virtual ~Backend() = default;
  virtual const char* name() const = 0;         // "mujoco"
  virtual const char* description() const = 0;  // one line for --help
  // Writes the target's files into `dir` (an empty folder the driver created,
  // later renamed to OUTDIR/<target>). Returns false after adding errors.
  virtual bool emit(const Object& obj, const std::string& dir, Diagnostics& diags) const = 0;
};

const std::vector<const Backend*>& all_backends();
const Backend* find_backend(const std::string& name);

}  // namespace efc
