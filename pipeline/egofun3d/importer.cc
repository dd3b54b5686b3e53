#include "pipeline/egofun3d/importer.h"

#include <filesystem>

#include "pipeline/egofun3d/dataset_index.h"
#include "pipeline/egofun3d/video_import.h"

namespace efc::egofun3d {

namespace fs = std::filesystem;

int import_dataset(const ImportOptions& options, Diagnostics& diags, const std::function<void()>& flush) {
  JsonDoc index;
  std::vector<VideoEntry> entries;
  const bool usable = read_dataset_index(options.dataset, diags, &index, &entries);
  flush();
  if (!usable) {
    // No index at all (missing, unreadable) is a file that cannot be read
    // (exit 2); one that parses but is no list of videos is bad input (1).
    const bool missing = !fs::is_regular_file(fs::path(options.dataset) / "dataset_metadata.json");
    return missing ? 2 : 1;
  }
  std::error_code ec;
  fs::create_directories(options.output, ec);
  if (ec || !fs::is_directory(options.output, ec)) {
    diags.error("E1048", options.output, 0, 0, "", "the output folder cannot be created (" + ec.message() + ")");
    flush();
    return 2;
  }
  int imported = 0, failed = 0;
  bool io_failure = false;
  for (size_t i = 0; i < entries.size(); ++i) {
    const VideoEntry& e = entries[i];
    const std::string prefix = "import: " + std::to_string(i + 1) + "/" + std::to_string(entries.size()) + " " +
                               (e.video_name.empty() ? "(entry " + std::to_string(i) + ")" : e.video_name) + ": ";
    if (!e.ok) {
      ++failed;
      diags.note(prefix + "failed (its dataset_metadata.json entry is wrong), nothing written");
      flush();
      continue;
    }
    VideoResult r = import_video(e, index, options.output, diags);
    if (r.ok) {
      ++imported;
      diags.note(prefix + r.summary);
    } else {
      ++failed;
      io_failure = io_failure || r.io_failure;
      diags.note(prefix + "failed, nothing written");
    }
    flush();
  }
  if (imported > 0)
    diags.note("import: " + std::to_string(imported) + " of " + std::to_string(entries.size()) +
               " videos imported into " + options.output +
               ". EgoFun3D has no depth: before `efc infer`, put an external depth model's maps in each "
               "SEQ/depth/ (16-bit PNG, millimetres, one per frame, the frames' size)");
  if (failed > 0)
    diags.note("import: " + std::to_string(failed) + " of " + std::to_string(entries.size()) + " videos failed");
  flush();
  if (io_failure) return 2;
  return failed > 0 ? 1 : 0;
}

}  // namespace efc::egofun3d
