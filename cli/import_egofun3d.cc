// efc import-egofun3d DATASET -o DIR: hands the command to the importer
// program, efc-import-egofun3d, built next to efc. The importer decodes
// video (FFmpeg) and reads HDF5, ~150 shared libraries that every other efc
// command would otherwise load at start-up; so efc links neither and execs
// the importer with the arguments it was given.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>

#include "cli/commands.h"

namespace efc {

int cmd_import_egofun3d(Report& report, const std::vector<std::string>& args) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  const fs::path importer = ec ? fs::path() : self.parent_path() / "efc-import-egofun3d";
  if (importer.empty() || access(importer.c_str(), X_OK) != 0) {
    return report.fail("E1049",
                       "the EgoFun3D importer program is missing: " +
                           (importer.empty() ? std::string("efc-import-egofun3d") : importer.string()),
                       kExitUsage,
                       "build it: cmake --build build --target efc-import-egofun3d (it needs FFmpeg and HDF5: "
                       "scripts/setup installs them)");
  }
  std::vector<std::string> argv_text{importer.string()};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  report.flush();
  std::cerr.flush();
  execv(importer.c_str(), argv.data());
  return report.fail("E1049", "cannot run " + importer.string() + ": " + std::strerror(errno), kExitUsage);
}

}  // namespace efc
