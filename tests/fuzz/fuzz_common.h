// Shared by the fuzz targets: the spec folder they read against, and the
// checks every run's diagnostics must pass (a failed check prints what it saw
// and traps, which libFuzzer reports as a crash with the input saved).
#pragma once

#include <string>
#include <string_view>

#include "compiler/diagnostics.h"

namespace efc_fuzz {

// A temporary folder made once per process (removed at exit) holding
// meshes/faucet_handle.obj and meshes/faucet_spout.obj (empty files: the
// front-end only checks that a mesh path names a regular file inside the
// spec's folder), so the examples' mesh paths resolve as they do in examples/.
const std::string& base_dir();

// Prints `what` (and the input, escaped, when short) to stderr and traps.
[[noreturn]] void fail(const std::string& what, std::string_view input);

// Every diagnostic has a catalogued code (efc explain knows it), a position
// inside the text (line 1..lines+1 or 0 = unknown, column >= 0), and formats
// as text and as one valid JSON line. `rejected` = the front-end returned
// nothing, which must come with at least one error.
void check_diagnostics(const efc::Diagnostics& diags, std::string_view text, bool rejected,
                       const char* stage);

}  // namespace efc_fuzz
