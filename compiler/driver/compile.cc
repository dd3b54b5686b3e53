// efc compile: all-or-nothing. Every target of every spec is written into a
// staging folder next to OUTDIR; only when all succeeded are the target folders
// moved into place (rename), so an error leaves OUTDIR untouched.
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <set>

#include "backends/backend.h"
#include "compiler/core/load.h"
#include "compiler/driver/commands.h"

namespace fs = std::filesystem;

namespace efc {
namespace {

struct Staging {
  fs::path path;
  explicit Staging(const fs::path& parent) {
    std::string tmpl = (parent / ".efc-staging-XXXXXX").string();
    if (mkdtemp(tmpl.data())) path = tmpl;
  }
  ~Staging() {
    std::error_code ec;
    if (!path.empty()) fs::remove_all(path, ec);
  }
};

}  // namespace

int cmd_compile(const std::vector<std::string>& specs, const std::vector<std::string>& targets,
                const std::string& out_dir, const CommonOptions& common) {
  std::vector<const Backend*> chosen;
  std::set<std::string> seen;
  for (const std::string& t : targets) {
    if (t == "all") {
      for (const Backend* b : all_backends())
        if (seen.insert(b->name()).second) chosen.push_back(b);
      continue;
    }
    const Backend* b = find_backend(t);
    if (!b) {
      std::string names;
      for (const Backend* x : all_backends()) names += std::string(" ") + x->name();
      std::cerr << "efc compile: unknown target '" << t << "' (targets: all" << names << ")\n";
      return 2;
    }
    if (seen.insert(b->name()).second) chosen.push_back(b);
  }

  // Read and check every spec first: no output at all if any is wrong.
  std::vector<Object> objects;
  int rc = 0;
  for (const std::string& spec : specs) {
    Diagnostics diags;
    LoadOptions opts;
    opts.allow_absolute_paths = common.allow_absolute_paths;
    bool io_error = false;
    std::optional<Object> obj = load_spec(spec, opts, diags, &io_error);
    diags.print(std::cerr, common.json_diagnostics);
    if (!obj) {
      rc = std::max(rc, io_error ? 2 : 1);
      continue;
    }
    objects.push_back(std::move(*obj));
  }
  if (rc != 0) return rc;
  if (objects.size() > 1) {
    std::set<std::string> names;
    for (const Object& o : objects)
      if (!names.insert(o.name).second) {
        std::cerr << "efc compile: two specs are both named '" << o.name
                  << "'; their outputs would collide in " << out_dir << "/" << o.name << "\n";
        return 1;
      }
  }

  const fs::path out = fs::absolute(out_dir);
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec)) {
    std::cerr << "efc compile: '" << out_dir << "' exists and is not a folder\n";
    return 2;
  }
  const fs::path parent = out.parent_path();
  if (!fs::is_directory(parent, ec)) {
    std::cerr << "efc compile: the folder '" << parent.string() << "' does not exist\n";
    return 2;
  }
  Staging staging(parent);
  if (staging.path.empty()) {
    std::cerr << "efc compile: cannot write into '" << parent.string() << "'\n";
    return 2;
  }

  // (relative folder under OUTDIR) for every emitted target.
  std::vector<fs::path> produced;
  for (const Object& obj : objects) {
    for (const Backend* b : chosen) {
      const fs::path rel = objects.size() > 1 ? fs::path(obj.name) / b->name() : fs::path(b->name());
      const fs::path dir = staging.path / rel;
      fs::create_directories(dir, ec);
      Diagnostics diags;
      const bool ok = !ec && b->emit(obj, dir.string(), diags);
      diags.print(std::cerr, common.json_diagnostics);
      if (ec) std::cerr << "efc compile: cannot create " << dir.string() << ": " << ec.message() << "\n";
      if (!ok) return 2;  // backends fail only on I/O (the IR was checked)
      produced.push_back(rel);
      if (!common.json_diagnostics)
        std::cerr << "compiled " << obj.name << " -> " << (fs::path(out_dir) / rel).string() << "\n";
    }
  }

  // Commit: move each target folder into place, replacing an older one.
  fs::create_directories(out, ec);
  if (ec) {
    std::cerr << "efc compile: cannot create '" << out_dir << "': " << ec.message() << "\n";
    return 2;
  }
  for (const fs::path& rel : produced) {
    const fs::path dest = out / rel;
    fs::create_directories(dest.parent_path(), ec);
    fs::remove_all(dest, ec);
    fs::rename(staging.path / rel, dest, ec);
    if (ec) {
      std::cerr << "efc compile: cannot move output into '" << dest.string() << "': " << ec.message() << "\n";
      return 2;
    }
  }
  return 0;
}

}  // namespace efc
