#include "batch/process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "batch/atomic_file.h"

namespace efc::batch {

namespace {

// In the child between fork and exec only async-signal-safe calls: write a
// message and leave.
[[noreturn]] void child_fail(const char* what, int err) {
  const char* reason = std::strerror(err);
  const char* prefix = "efc batch: ";
  (void)!::write(2, prefix, std::strlen(prefix));
  (void)!::write(2, what, std::strlen(what));
  (void)!::write(2, ": ", 2);
  (void)!::write(2, reason, std::strlen(reason));
  (void)!::write(2, "\n", 1);
  _exit(127);
}

int open_out(const std::string& path) {
  return ::open(path.empty() ? "/dev/null" : path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
}

}  // namespace

pid_t spawn(const std::vector<std::string>& argv, const SpawnOptions& opts, std::string* error) {
  // Everything the child needs is prepared before fork.
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const int in = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  const int out = open_out(opts.stdout_file);
  const int err = open_out(opts.stderr_file);
  if (in < 0 || out < 0 || err < 0) {
    *error = std::string("cannot open the job's log files: ") + std::strerror(errno);
    for (int fd : {in, out, err})
      if (fd >= 0) ::close(fd);
    return -1;
  }
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    *error = std::string("cannot start a process: ") + std::strerror(errno);
    ::close(in), ::close(out), ::close(err);
    return -1;
  }
  if (pid == 0) {
    setpgid(0, 0);
    // Die with the batch: a SIGKILLed batch must not leave jobs writing into
    // folders the next run clears. (Checked against a parent already gone.)
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(137);
    // The batch's own handlers and mask must not carry over.
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    signal(SIGPIPE, SIG_DFL);
    if (dup2(in, 0) < 0 || dup2(out, 1) < 0 || dup2(err, 2) < 0) _exit(127);
    if (!opts.cwd.empty() && chdir(opts.cwd.c_str()) != 0) child_fail(opts.cwd.c_str(), errno);
    // A bare name (sbatch) is looked up in PATH; the jobs get an absolute path.
    execvp(args[0], args.data());
    child_fail(args[0], errno);
  }
  // Also here, so that the group exists before anyone signals it.
  setpgid(pid, pid);
  ::close(in), ::close(out), ::close(err);
  return pid;
}

int wait_any(Exited* out) {
  int status = 0;
  rusage ru{};
  const pid_t pid = wait4(-1, &status, 0, &ru);
  if (pid < 0) return errno == EINTR ? 0 : -1;
  out->pid = pid;
  out->signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  out->exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + out->signal;
  out->peak_rss_mb = static_cast<double>(ru.ru_maxrss) / 1024.0;  // Linux: KiB
  return 1;
}

int run_capture(const std::vector<std::string>& argv, std::string* out, std::string* err) {
  char tmpl[] = "/tmp/efc-batch-capture-XXXXXX";
  if (!mkdtemp(tmpl)) {
    *out = std::string("cannot make a temporary folder: ") + std::strerror(errno);
    return -1;
  }
  const std::string dir = tmpl;
  SpawnOptions opts;
  opts.stdout_file = dir + "/out";
  opts.stderr_file = dir + "/err";
  std::string error;
  const pid_t pid = spawn(argv, opts, &error);
  int code = -1;
  if (pid < 0) {
    *out = error;
  } else {
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    read_whole_file(opts.stdout_file, out);
    read_whole_file(opts.stderr_file, err);
  }
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  return code;
}

}  // namespace efc::batch
