// One small interface for every target, registered in one table (registry.cc).
// A backend reads a resolved, checked IR and generates its whole output folder
// in memory; the CLI writes it (all or nothing). It never re-validates. A
// feature it cannot express becomes a W0900 warning located in the spec,
// naming the feature and what was emitted instead, never a silent drop.
#pragma once

#include <string>
#include <vector>

#include "backends/common/output_file.h"
#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc {

class Backend {
 public:
  virtual ~Backend() = default;
  virtual const char* name() const = 0;         // "mujoco": also the output folder's name
  virtual const char* description() const = 0;  // one line for --help
  // Other names `--target` accepts ("isaac" for "isaaclab").
  virtual std::vector<std::string> aliases() const { return {}; }
  // The target folder's files, paths relative to it ("meshes/a.stl"),
  // deterministic (same object, same bytes). Returns false after adding an
  // error; warnings go to diags either way.
  virtual bool generate(const Object& obj, Diagnostics& diags, std::vector<OutputFile>* files) const = 0;

  // generate(), then write the files into `dir` (an existing folder): for
  // tests and tools that want the folder without the CLI's staging.
  bool emit(const Object& obj, const std::string& dir, Diagnostics& diags) const;
};

const std::vector<const Backend*>& all_backends();
// By name or alias; nullptr when none has it.
const Backend* find_backend(const std::string& name);

}  // namespace efc
