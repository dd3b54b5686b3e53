#include "pipeline/egofun3d/dataset_index.h"

#include <filesystem>
#include <set>

#include "pipeline/egofun3d/names.h"

namespace efc::egofun3d {
namespace {

constexpr const char* kCode = "E1040";

std::string join(const std::string& dir, const std::string& rel) {
  return (std::filesystem::path(dir) / rel).lexically_normal().string();
}

}  // namespace

std::string id_text(const nlohmann::json& id) {
  if (id.is_string()) return id.get<std::string>();
  if (id.is_number_integer()) return std::to_string(id.get<long long>());
  return id.dump();
}

bool read_dataset_index(const std::string& dataset_dir, Diagnostics& diags, JsonDoc* doc,
                        std::vector<VideoEntry>* out) {
  out->clear();
  const std::string path = join(dataset_dir, "dataset_metadata.json");
  std::error_code ec;
  if (!std::filesystem::is_directory(dataset_dir, ec)) {
    diags.error(kCode, dataset_dir, 0, 0, "", "the dataset folder does not exist",
                "pass the EgoFun3D folder that holds dataset_metadata.json");
    return false;
  }
  if (!doc->read(path, kCode, diags)) return false;
  if (!doc->root().is_array()) {
    doc->error(diags, kCode, "", "dataset_metadata.json must be a list of videos, found " +
                                     frontend::json_kind_phrase(doc->root()));
    return false;
  }
  if (doc->root().empty()) {
    doc->error(diags, kCode, "", "dataset_metadata.json lists no videos");
    return false;
  }
  std::set<std::string> folders;
  for (size_t i = 0; i < doc->root().size(); ++i) {
    VideoEntry e;
    e.pointer = pointer_join("", i);
    if (!doc->root()[i].is_object()) {
      doc->error(diags, kCode, e.pointer, "a video entry must be an object, found " +
                                              frontend::json_kind_phrase(doc->root()[i]));
      e.ok = false;
      e.folder = "entry_" + std::to_string(i);
      out->push_back(std::move(e));
      continue;
    }
    const size_t before = diags.error_count();
    auto str = [&](const char* key) { return doc->string(diags, kCode, e.pointer, key).value_or(""); };
    auto path_of = [&](const char* key) {
      const size_t errors = diags.error_count();
      const std::string rel = str(key);
      if (diags.error_count() == errors && rel.empty())
        doc->error(diags, kCode, pointer_join(e.pointer, key), std::string("\"") + key + "\" is empty");
      return rel.empty() ? rel : join(dataset_dir, rel);
    };
    e.video_name = str("video_name");
    if (const nlohmann::json* id = doc->member(diags, kCode, e.pointer, "function_instance_id")) {
      if (!id->is_string() && !id->is_number_integer())
        doc->error(diags, kCode, pointer_join(e.pointer, "function_instance_id"),
                   "\"function_instance_id\" must be an integer or a string");
      e.function_instance_id = *id;
    }
    // source is informational ("egoexo4d", "hoi4d", ...); absent is fine.
    if (const nlohmann::json* s = doc->member(diags, kCode, e.pointer, "source", false); s && s->is_string())
      e.source = s->get<std::string>();
    // The video: the crop when the entry has one (what the reference loader
    // reads for EgoExo4D), else the original.
    const nlohmann::json* cropped = doc->member(diags, kCode, e.pointer, "cropped_video_path", false);
    if (cropped && cropped->is_string() && !cropped->get<std::string>().empty()) {
      e.video = path_of("cropped_video_path");
      e.cropped_video = true;
    } else if (doc->member(diags, kCode, e.pointer, "original_video_path", false)) {
      e.video = path_of("original_video_path");
    } else if (doc->member(diags, kCode, e.pointer, "video_path", false)) {
      e.video = path_of("video_path");
    } else {
      doc->error(diags, kCode, e.pointer, "missing \"cropped_video_path\" (or \"original_video_path\")");
    }
    e.extrinsics = path_of("camera_extrinsics_path");
    e.intrinsics = path_of("camera_intrinsics_path");
    e.masks = path_of("video_mask_path");
    e.geometry_type = str("geometry_type");
    e.geometry = path_of("geometry_path");
    e.part_annotation = path_of("part_annotation_path");
    e.articulation = path_of("articulation_path");
    e.function_annotation = path_of("function_annotation_path");
    if (!e.geometry_type.empty() && e.geometry_type != "mesh" && e.geometry_type != "point cloud" &&
        e.geometry_type != "point_cloud" && e.geometry_type != "pointcloud")
      doc->error(diags, kCode, pointer_join(e.pointer, "geometry_type"),
                 "\"geometry_type\" '" + e.geometry_type + "' is unknown: expected \"mesh\" or \"point cloud\"");
    e.ok = diags.error_count() == before;
    if (e.ok) {
      e.folder = sanitize_folder(e.video_name);
      if (!folders.insert(e.folder).second) {
        doc->error(diags, kCode, pointer_join(e.pointer, "video_name"),
                   "video '" + e.video_name + "' would be written to folder '" + e.folder +
                       "', which an earlier video already uses",
                   "video names must differ (after characters other than letters, digits, '.', '_', '-' "
                   "become '_')");
        e.ok = false;
      }
    }
    if (e.folder.empty()) e.folder = sanitize_folder(e.video_name);
    out->push_back(std::move(e));
  }
  return true;
}

}  // namespace efc::egofun3d
