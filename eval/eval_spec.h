// The two specs efc eval compares, loaded with the compiler's own loader and
// placed in the world by their "x-efc-object-to-world" (world_frame.h).
#pragma once

#include <optional>
#include <string>

#include "compiler/diagnostics.h"
#include "compiler/ir.h"
#include "eval/world_frame.h"

namespace efc::eval {

struct PlacedSpec {
  Object object;
  WorldFrame world;
};

// The truth must load: nullopt with every problem in diags (*io_error when
// the file could not be read at all: the CLI's exit 2 rather than 1).
std::optional<PlacedSpec> load_truth(const std::string& path, bool allow_absolute_paths, Diagnostics& diags,
                                     bool* io_error);

// A prediction that is missing, does not load or has a malformed frame is no
// error of efc eval's input: it is a failed prediction, scored as such.
// nullopt with *why (one line: the first problem) in that case.
std::optional<PlacedSpec> load_prediction(const std::string& path, bool allow_absolute_paths, std::string* why);

}  // namespace efc::eval
