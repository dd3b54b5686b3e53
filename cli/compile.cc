// efc compile SPEC... --target T... -o OUTDIR: all-or-nothing. Every target of
// every spec is generated in memory and written into a staging folder next to
// OUTDIR; only when all succeeded are the target folders moved into place
// (rename), so an error leaves OUTDIR untouched.
#include <unistd.h>

#include <filesystem>
#include <set>

#include "backends/backend.h"
#include "backends/common/temp_dir.h"
#include "cli/commands.h"

namespace fs = std::filesystem;

namespace efc {
namespace {

// A backend and the folder its output goes to: the target as the user named
// it (shared/spec/cli.md's `isaac` and `behavior` write OUTDIR/isaac/ and
// OUTDIR/behavior/), or the backend's own name for `all`.
struct Chosen {
  const Backend* backend;
  std::string folder;
};

// The backends `targets` names, each once (the first spelling wins; "all" is
// every one); nullopt after reporting an unknown name.
std::optional<std::vector<Chosen>> choose_backends(Report& report, const std::vector<std::string>& targets) {
  std::vector<Chosen> chosen;
  std::set<std::string> seen;
  for (const std::string& t : targets) {
    if (t == "all") {
      for (const Backend* b : all_backends())
        if (seen.insert(b->name()).second) chosen.push_back({b, b->name()});
      continue;
    }
    const Backend* b = find_backend(t);
    if (!b) {
      std::string names;
      for (const Backend* x : all_backends()) {
        names += std::string(" ") + x->name();
        for (const std::string& alias : x->aliases()) names += " " + alias;
      }
      report.fail("E0910", "unknown target '" + t + "' (targets: all" + names + ")", kExitUsage);
      return std::nullopt;
    }
    if (seen.insert(b->name()).second) chosen.push_back({b, t});
  }
  return chosen;
}

}  // namespace

int cmd_compile(Report& report, const std::vector<std::string>& specs,
                const std::vector<std::string>& targets, const std::string& out_dir) {
  const auto chosen = choose_backends(report, targets);
  if (!chosen) return kExitUsage;

  // Read and check every spec first: no output at all if any is wrong.
  int rc = kExitOk;
  const std::vector<Object> objects = load_all(report, specs, &rc);
  if (rc != kExitOk) return rc;
  if (objects.size() > 1) {
    std::set<std::string> names;
    for (const Object& o : objects)
      if (!names.insert(o.name).second)
        return report.fail("E0911",
                           "two specs are both named '" + o.name + "'; their outputs would collide in " +
                               out_dir + "/" + o.name,
                           kExitBadInput);
  }

  const fs::path out = fs::absolute(out_dir);
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec))
    return report.fail("E0910", "'" + out_dir + "' exists and is not a folder", kExitUsage);
  const fs::path parent = out.parent_path();
  if (!fs::is_directory(parent, ec))
    return report.fail("E0900", "the folder '" + parent.string() + "' does not exist", kExitUsage);
  TempDir staging(parent, ".efc-staging");
  if (staging.path().empty())
    return report.fail("E0900", "cannot write into '" + parent.string() + "'", kExitUsage);

  // Generate every target in memory and stage it: (folder under OUTDIR) each.
  std::vector<fs::path> produced;
  for (const Object& obj : objects) {
    for (const Chosen& c : *chosen) {
      const Backend* b = c.backend;
      const fs::path rel = objects.size() > 1 ? fs::path(obj.name) / c.folder : fs::path(c.folder);
      const fs::path dir = staging.path() / rel;
      std::vector<OutputFile> files;
      // Backends fail only on what the checks cannot see (a mesh that did not
      // load) or on I/O: exit 2.
      if (!b->generate(obj, report.diags(), &files)) {
        report.flush();
        return kExitUsage;
      }
      fs::create_directories(dir, ec);
      if (ec) return report.fail("E0900", "cannot create " + dir.string() + ": " + ec.message(), kExitUsage);
      if (!write_output_files(dir.string(), files, report.diags())) {
        report.flush();
        return kExitUsage;
      }
      report.flush();
      produced.push_back(rel);
      report.note("compiled " + obj.name + " -> " + (fs::path(out_dir) / rel).string());
    }
  }

  // Commit: move each target folder into place, replacing an older one.
  fs::create_directories(out, ec);
  if (ec) return report.fail("E0900", "cannot create '" + out_dir + "': " + ec.message(), kExitUsage);
  for (const fs::path& rel : produced) {
    const fs::path dest = out / rel;
    fs::create_directories(dest.parent_path(), ec);
    fs::remove_all(dest, ec);
    fs::rename(staging.path() / rel, dest, ec);
    if (ec)
      return report.fail("E0900", "cannot move output into '" + dest.string() + "': " + ec.message(),
                         kExitUsage);
  }
  return kExitOk;
}

}  // namespace efc
