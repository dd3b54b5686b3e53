// Running the built efc program from a test: one runner for every CLI test.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace efc_test {

struct CliResult {
  int exit_code = -1;
  bool signaled = false;
  std::string err, out;
};

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs build/efc with `args` (already shell-quoted), from `cwd` when given,
// capturing stdout and stderr.
inline CliResult run_efc(const std::string& args, const std::string& cwd = "") {
  namespace fs = std::filesystem;
  static int counter = 0;
  const fs::path dir = fs::temp_directory_path() /
                       ("efc-cli-run-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
  fs::create_directories(dir);
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  std::string cmd = std::string(EFC_BINARY_DIR) + "/efc " + args + " >" + out.string() + " 2>" +
                    err.string() + " </dev/null";
  if (!cwd.empty()) cmd = "cd '" + cwd + "' && " + cmd;
  const int status = std::system(cmd.c_str());
  CliResult r;
  // std::system runs a shell: a signal in efc shows as exit 128+N from the shell.
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.signaled = WIFSIGNALED(status) || r.exit_code > 128;
  r.out = read_file(out);
  r.err = read_file(err);
  fs::remove_all(dir);
  return r;
}

}  // namespace efc_test
