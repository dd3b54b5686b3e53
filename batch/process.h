// Child processes: the jobs (fork + exec of the efc program, each in its own
// process group so that a signal reaches everything it started) and short
// helper commands (sbatch). Plain POSIX, no threads: wait4 gives each job's
// exit status and its peak resident memory (ru_maxrss) at once.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace efc::batch {

struct SpawnOptions {
  std::string cwd;          // working folder ("" = this one)
  std::string stdout_file;  // created or truncated ("" = /dev/null)
  std::string stderr_file;
};

// Starts argv[0] (a path) with `argv` in a new process group whose id is its
// pid, stdin from /dev/null, and SIGKILL sent to it should this process die
// first (PR_SET_PDEATHSIG: a batch killed with SIGKILL leaves no job running
// on). A failed exec is the child's exit 127 with the reason on its stderr.
// Returns the pid, or -1 with *error when fork fails.
pid_t spawn(const std::vector<std::string>& argv, const SpawnOptions& opts, std::string* error);

struct Exited {
  pid_t pid = -1;
  int exit_code = 0;  // its status, or 128 + signal
  int signal = 0;
  double peak_rss_mb = 0;
};

// Waits for any child (wait4). Returns 1 with *out, 0 when interrupted by a
// signal (EINTR), -1 when there is no child left.
int wait_any(Exited* out);

// Runs argv to its end, capturing stdout and stderr; the exit code (128 +
// signal), or -1 with *out holding why when it could not be started.
int run_capture(const std::vector<std::string>& argv, std::string* out, std::string* err);

}  // namespace efc::batch
