#include "compiler/core/load.h"

#include "compiler/core/resolve.h"
#include "compiler/frontend/check.h"
#include "compiler/frontend/json_reader.h"

namespace efc {

std::optional<Object> load_spec(const std::string& path, const LoadOptions& opts,
                                Diagnostics& diags, bool* io_error) {
  if (io_error) *io_error = false;
  ReadOptions read_opts;
  read_opts.allow_absolute_paths = opts.allow_absolute_paths;
  bool io = false;
  std::string text;
  std::optional<Object> obj = read_spec_file(path, read_opts, diags, &io, &text);
  if (io_error) *io_error = io;
  if (!obj) return std::nullopt;
  // The checks' diagnostics point into the spec too: show its lines.
  auto finish = [&](bool ok) -> std::optional<Object> {
    diags.attach_source_lines(path, text);
    if (!ok) return std::nullopt;
    return std::move(obj);  // the Object, its positions included, is not copied
  };
  // Shape errors and structural errors are reported together: the checks run
  // on whatever the reader could build, so one run shows every problem.
  check_structure(*obj, diags);
  if (diags.has_errors()) return finish(false);
  resolve(*obj, diags);
  if (diags.has_errors()) return finish(false);
  check_resolved(*obj, diags);
  if (diags.has_errors()) return finish(false);
  return finish(true);
}

}  // namespace efc
