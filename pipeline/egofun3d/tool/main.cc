// efc-import-egofun3d DATASET -o DIR: the EgoFun3D importer as its own
// program. FFmpeg and HDF5 load ~150 shared libraries, so the efc program
// does not link them; `efc import-egofun3d` execs this program (found next
// to efc) with the same arguments. Messages are efc's (compiler/diagnostics.h):
// `file:line:col: error[CODE]: message`, or JSON lines with
// --diagnostics-format json. Exit codes as efc's (shared/spec/cli.md).
#include <CLI/CLI.hpp>

#include <cstring>
#include <exception>
#include <iostream>

#include "compiler/diagnostics.h"
#include "pipeline/egofun3d/importer.h"

namespace {

bool wants_json(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--diagnostics-format=json") == 0) return true;
    if (std::strcmp(argv[i], "--diagnostics-format") == 0 && i + 1 < argc && std::strcmp(argv[i + 1], "json") == 0)
      return true;
  }
  return false;
}

int run(int argc, char** argv) {
  CLI::App app{"efc import-egofun3d: one efc sequence (with truth/) per video of an EgoFun3D-layout dataset",
               "efc import-egofun3d"};
  efc::egofun3d::ImportOptions options;
  std::string format = "text";
  bool allow_absolute = false;  // accepted as efc's commands accept it; paths here are the dataset's
  app.add_option("DATASET", options.dataset, "the dataset folder (holds dataset_metadata.json)")->required();
  app.add_option("-o,--output", options.output, "folder to write one sequence per video into")->required();
  app.add_option("--diagnostics-format", format, "text (default) or json (one JSON object per line)")
      ->check(CLI::IsMember({"text", "json"}));
  app.add_flag("--allow-absolute-paths", allow_absolute, "accepted for symmetry with efc's commands; no effect");
  efc::Diagnostics diags;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0 || !wants_json(argc, argv)) {
      const int rc = app.exit(e);
      return rc == 0 ? 0 : 2;
    }
    diags.error("E0910", "", 0, 0, "", e.what(), "see efc import-egofun3d --help");
    diags.print(std::cerr, true);
    return 2;
  }
  const bool json = format == "json";
  auto flush = [&] {
    diags.print(std::cerr, json);
    std::cerr.flush();
    diags.clear();
  };
  return efc::egofun3d::import_dataset(options, diags, flush);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "efc-import-egofun3d: internal error: %s\n", e.what());
    return 2;
  }
}
