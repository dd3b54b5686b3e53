#include "eval/eval_spec.h"

#include <cmath>
#include <filesystem>
#include <fstream>

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

// A truth spec inside a sequence's truth/ folder is in its own object frame
// and its place in the world is truth/object_pose.json (sequence.md): used
// when the spec itself has no "x-efc-object-to-world".
static bool pose_beside(const std::string& spec_path, Diagnostics& diags, WorldFrame* out) {
  const std::filesystem::path pose = std::filesystem::path(spec_path).parent_path() / "object_pose.json";
  std::ifstream in(pose);
  if (!in) return true;
  const nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
  const auto bad = [&](const std::string& why) {
    diags.error("E1020", pose.string(), 0, 0, "/object_to_world", why, "write 16 numbers, row-major, last row [0, 0, 0, 1]");
    return false;
  };
  if (doc.is_discarded() || !doc.is_object() || !doc.contains("object_to_world")) return bad("no \"object_to_world\" in it");
  std::string problem, suffix;
  return read_transform(doc["object_to_world"], "\"object_to_world\"", out, &problem, &suffix) || bad(problem);
}

std::optional<PlacedSpec> load_truth(const std::string& path, bool allow_absolute_paths, Diagnostics& diags,
                                     bool* io_error) {
  *io_error = false;
  std::optional<PlacedSpec> placed = load_placed(path, allow_absolute_paths, diags, io_error);
  if (placed && !placed->object.extensions.count("x-efc-object-to-world") &&
      !pose_beside(path, diags, &placed->world))
    return std::nullopt;
  return placed;
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
