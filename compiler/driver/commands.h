// The efc subcommands. Each returns the process exit code.
#pragma once

#include <string>
#include <vector>

namespace efc {

struct CommonOptions {
  bool json_diagnostics = false;  // --diagnostics-format json
  bool allow_absolute_paths = false;
};

int run_cli(int argc, char** argv);

int cmd_check(const std::vector<std::string>& specs, bool dump_ir, const CommonOptions& common);
int cmd_compile(const std::vector<std::string>& specs, const std::vector<std::string>& targets,
                const std::string& out_dir, const CommonOptions& common);
int cmd_explain(const std::string& code, bool list);
// efc parity: the MuJoCo harness against the compiled Bullet program (parity.cc).
int cmd_parity(const std::string& spec, const std::string& profile, double duration, double dt,
               const std::string& bullet_exe, const std::string& csv_dir, const CommonOptions& common);

}  // namespace efc
