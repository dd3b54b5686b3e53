// The front door of the compiler: read a spec (by extension), fill defaults
// and mass properties (resolve), and check every type rule. Every later stage
// (backends, the harness) takes the Object this returns.
#pragma once

#include <optional>
#include <string>

#include "compiler/diagnostics.h"
#include "compiler/ir.h"

namespace efc {

struct LoadOptions {
  bool allow_absolute_paths = false;
};

// Returns the resolved, checked object, or nullopt when any error was found
// (all of them are in diags). *io_error is set when the file could not be read
// (the CLI's exit code 2 rather than 1).
std::optional<Object> load_spec(const std::string& path, const LoadOptions& opts,
                                Diagnostics& diags, bool* io_error = nullptr);

}  // namespace efc
