// write_infer_output (infer.h): OUT/spec.json, OUT/meshes/, OUT/report.json,
// all or nothing.
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "compiler/core/load.h"
#include "pipeline/infer/infer.h"
#include "sequence/sequence.h"

namespace efc::pipeline {

namespace fs = std::filesystem;

namespace {

// A folder beside the output, removed unless released.
class Staging {
 public:
  explicit Staging(const fs::path& final_dir) {
    std::string tmpl = (final_dir.parent_path() / ("." + final_dir.filename().string() + ".partial-XXXXXX")).string();
    if (mkdtemp(tmpl.data())) path_ = tmpl;
  }
  ~Staging() {
    std::error_code ec;
    if (!path_.empty()) fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }
  void release() { path_.clear(); }

 private:
  fs::path path_;
};

// An earlier `efc infer` output: spec.json and report.json, maybe meshes/.
bool is_infer_output(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir / "spec.json") || !fs::exists(dir / "report.json")) return false;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string n = e.path().filename().string();
    if (n != "spec.json" && n != "report.json" && n != "meshes") return false;
  }
  return !ec;
}

}  // namespace

int write_infer_output(const InferResult& result, const std::string& out_dir, Diagnostics& diags) {
  const fs::path final_dir = fs::absolute(out_dir).lexically_normal();
  std::error_code ec;
  if (fs::exists(final_dir) && (!fs::is_directory(final_dir) ||
                                (!fs::is_empty(final_dir, ec) && !is_infer_output(final_dir)))) {
    diags.error("E0910", out_dir, 0, 0, "", "'" + out_dir + "' exists and is not an efc infer output; not replacing it",
                "choose another -o or remove it");
    return 2;
  }
  fs::create_directories(final_dir.parent_path(), ec);
  Staging staging(final_dir);
  if (staging.path().empty()) {
    diags.error("E0900", out_dir, 0, 0, "", "cannot create a folder beside '" + out_dir + "'");
    return 2;
  }
  const fs::path dir = staging.path();
  fs::create_directories(dir / "meshes", ec);
  std::string error;
  for (const auto& [rel, mesh] : result.meshes) {
    if (!write_obj((dir / rel).string(), mesh, &error)) {
      diags.error("E0900", (final_dir / rel).string(), 0, 0, "", "cannot write the mesh: " + error);
      return 2;
    }
  }
  if (!seq::write_text_file((dir / "spec.json").string(), result.spec.dump(2) + "\n", &error) ||
      !seq::write_text_file((dir / "report.json").string(), result.report.dump(2) + "\n", &error)) {
    diags.error("E0900", out_dir, 0, 0, "", "cannot write: " + error);
    return 2;
  }
  // The spec must compile: check it as `efc check` would, where it lies.
  Diagnostics check;
  LoadOptions lo;
  if (!load_spec((dir / "spec.json").string(), lo, check)) {
    diags.error("E1054", (final_dir / "spec.json").string(), 0, 0, "",
                "the inferred spec does not pass efc check (a defect of efc infer); nothing was written");
    for (Diagnostic d : check.items()) {
      if (d.severity != Severity::Error) continue;
      d.file = (final_dir / "spec.json").string();
      d.severity = Severity::Note;
      diags.add(d);
    }
    return 1;
  }
  if (fs::exists(final_dir)) fs::remove_all(final_dir, ec);
  fs::rename(dir, final_dir, ec);
  if (ec) {
    diags.error("E0900", out_dir, 0, 0, "", "cannot move the output into place: " + ec.message());
    return 2;
  }
  staging.release();
  return 0;
}

}  // namespace efc::pipeline
