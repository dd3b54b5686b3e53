#include "eval/eval_spec.h"

#include <filesystem>

#include "compiler/core/load.h"

namespace efc::eval {

namespace {

std::optional<PlacedSpec> load_placed(const std::string& path, bool allow_absolute_paths, Diagnostics& diags,
                                      bool* io_error) {
  LoadOptions opts;
  opts.allow_absolute_paths = allow_absolute_paths;
  std::optional<Object> obj = load_spec(path, opts, diags, io_error);
  if (!obj) return std::nullopt;
  PlacedSpec placed;
  if (!object_to_world(*obj, diags, &placed.world)) return std::nullopt;
  placed.object = std::move(*obj);
  return placed;
}

}  // namespace

std::optional<PlacedSpec> load_truth(const std::string& path, bool allow_absolute_paths, Diagnostics& diags,
                                     bool* io_error) {
  *io_error = false;
  return load_placed(path, allow_absolute_paths, diags, io_error);
}

std::optional<PlacedSpec> load_prediction(const std::string& path, bool allow_absolute_paths, std::string* why) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    *why = path + ": no prediction (the file does not exist)";
    return std::nullopt;
  }
  Diagnostics diags;
  bool io_error = false;
  std::optional<PlacedSpec> placed = load_placed(path, allow_absolute_paths, diags, &io_error);
  if (!placed) {
    *why = path + ": the prediction does not load";
    for (const Diagnostic& d : diags.items())
      if (d.severity == Severity::Error) {
        *why = format_text(d);
        *why = why->substr(0, why->find('\n'));  // the headline, not the notes under it
        break;
      }
  }
  return placed;
}

}  // namespace efc::eval
