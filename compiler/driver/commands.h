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

// --duration and --dt of play and parity: a positive duration (at most 1e5 s),
// 0 < dt <= 0.1 s and dt <= duration, at most 50 million steps. Prints why
// not (prefixed with `command`) and returns false when they are unusable.
bool check_timing(const char* command, double duration, double dt);

int cmd_check(const std::vector<std::string>& specs, bool dump_ir, const CommonOptions& common);
int cmd_compile(const std::vector<std::string>& specs, const std::vector<std::string>& targets,
                const std::string& out_dir, const CommonOptions& common);
int cmd_explain(const std::string& code, bool list);
// efc fmt and efc convert (fmt_convert.cc).
int cmd_fmt(const std::vector<std::string>& files, bool check_only, const CommonOptions& common);
int cmd_convert(const std::string& in, const std::string& out, const CommonOptions& common);
// efc parity: the MuJoCo harness against the compiled Bullet program (parity.cc).
int cmd_parity(const std::string& spec, const std::string& profile, double duration, double dt,
               const std::string& bullet_exe, const std::string& csv_dir, const CommonOptions& common);

}  // namespace efc
