// `efc import-egofun3d DATASET -o DIR`: one sequence folder per video of an
// EgoFun3D-layout dataset (shared/spec/efc-spec-v1.md, last section), with
// truth/. Each video is written to a hidden folder beside its target and
// renamed into place only once it is complete and passes the sequence
// checks, so a video that fails leaves nothing behind; the other videos
// still import.
#pragma once

#include <functional>
#include <string>

#include "compiler/diagnostics.h"

namespace efc::egofun3d {

struct ImportOptions {
  std::string dataset, output;
};

// Every problem goes to `diags`; `flush` is called after each video (and
// after the index is read) so messages appear as the import goes. Returns
// the exit code: 0 every video imported, 1 some video's data is wrong, 2 the
// index cannot be read or the output cannot be written.
int import_dataset(const ImportOptions& options, Diagnostics& diags, const std::function<void()>& flush);

}  // namespace efc::egofun3d
