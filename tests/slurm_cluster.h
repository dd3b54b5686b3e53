// A one-node Slurm cluster on loopback, for tests: munged, slurmctld and
// slurmd started in the foreground as this process's children, as the
// current user, with a generated slurm.conf, munge key and state in a fresh
// temporary folder, on free ports; no systemd, no cgroups, no root.
// Client commands (sbatch, squeue, scontrol, scancel) find it through
// SLURM_CONF, which start() sets for this process and its children. The
// destructor cancels the jobs it was told about, then stops every daemon it
// started, by pid (SIGTERM, then SIGKILL after 10 s), also when a test
// assertion failed half-way.
#pragma once

#include <fcntl.h>
#include <netinet/in.h>
#include <pwd.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace efc_test {

// `name` in PATH or in the sbin folders Debian installs daemons into (often
// not in a user's PATH); "" when absent.
inline std::string find_program(const std::string& name) {
  std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  path += ":/usr/sbin:/sbin:/usr/local/sbin";
  std::istringstream dirs(path);
  for (std::string d; std::getline(dirs, d, ':');) {
    if (d.empty()) continue;
    const std::string p = d + "/" + name;
    if (access(p.c_str(), X_OK) == 0) return p;
  }
  return "";
}

// A TCP port on 127.0.0.1 nobody listens on now (bound, read, released).
inline int free_port() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  socklen_t len = sizeof a;
  int port = -1;
  if (fd >= 0 && bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
      getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) == 0)
    port = ntohs(a.sin_port);
  if (fd >= 0) close(fd);
  return port;
}

// Runs a shell command, returning its stdout (and *rc its exit code).
inline std::string shell_output(const std::string& cmd, int* rc = nullptr) {
  std::string out;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  const int status = pclose(p);
  if (rc) *rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

class SlurmCluster {
 public:
  // The daemons and clients this needs; the names of those missing.
  static std::vector<std::string> missing_programs() {
    std::vector<std::string> out;
    for (const char* p : {"munged", "mungekey", "slurmctld", "slurmd", "sbatch", "squeue", "scontrol", "scancel"})
      if (find_program(p).empty()) out.push_back(p);
    return out;
  }

  SlurmCluster() = default;
  SlurmCluster(const SlurmCluster&) = delete;
  SlurmCluster& operator=(const SlurmCluster&) = delete;
  ~SlurmCluster() { stop(); }

  const std::filesystem::path& dir() const { return dir_; }

  // Starts the three daemons and waits until the node is idle (30 s at
  // most). False with *why; the logs say more (logs()).
  bool start(std::string* why) {
    namespace fs = std::filesystem;
    char tmpl[4096];
    std::snprintf(tmpl, sizeof tmpl, "%s/efc-slurm-XXXXXX", fs::temp_directory_path().c_str());
    if (!mkdtemp(tmpl)) return fail(why, "cannot make a temporary folder");
    dir_ = tmpl;
    // munged refuses a socket folder that is not world-executable.
    chmod(dir_.c_str(), 0755);
    fs::create_directories(dir_ / "state");
    fs::create_directories(dir_ / "spool");
    const std::string key = (dir_ / "munge.key").string();
    int rc = 0;
    const std::string out = shell_output(find_program("mungekey") + " --create --keyfile='" + key + "'", &rc);
    if (rc != 0) return fail(why, "mungekey failed: " + out);
    chmod(key.c_str(), 0400);
    const std::string socket = (dir_ / "munge.sock").string();
    munged_ = spawn({find_program("munged"), "--foreground", "--socket=" + socket, "--key-file=" + key,
                     "--pid-file=" + (dir_ / "munged.pid").string(), "--log-file=" + (dir_ / "munged.log").string(),
                     "--seed-file=" + (dir_ / "munge.seed").string(), "--origin=127.0.0.1"},
                    dir_ / "munged.out");
    if (!wait_until([&] { return fs::exists(socket); }, 10)) return fail(why, "munged did not create its socket");

    char host[256] = {0};
    gethostname(host, sizeof host - 1);
    std::string short_host = host;
    short_host = short_host.substr(0, short_host.find('.'));
    const passwd* pw = getpwuid(getuid());
    const std::string user = pw ? pw->pw_name : "root";
    const int ctld_port = free_port(), slurmd_port = free_port();
    if (ctld_port <= 0 || slurmd_port <= 0 || ctld_port == slurmd_port) return fail(why, "no free ports");
    const fs::path conf = dir_ / "slurm.conf";
    std::ofstream c(conf);
    c << "ClusterName=efctest\n"
      << "SlurmctldHost=" << short_host << "(127.0.0.1)\n"
      << "SlurmUser=" << user << "\nSlurmdUser=" << user << "\n"
      << "SlurmctldPort=" << ctld_port << "\nSlurmdPort=" << slurmd_port << "\n"
      << "AuthType=auth/munge\nCredType=cred/munge\nAuthInfo=socket=" << socket << "\n"
      << "StateSaveLocation=" << (dir_ / "state").string() << "\n"
      << "SlurmdSpoolDir=" << (dir_ / "spool").string() << "\n"
      << "SlurmctldPidFile=" << (dir_ / "slurmctld.pid").string() << "\n"
      << "SlurmdPidFile=" << (dir_ / "slurmd.pid").string() << "\n"
      << "SlurmctldLogFile=" << (dir_ / "slurmctld.log").string() << "\n"
      << "SlurmdLogFile=" << (dir_ / "slurmd.log").string()
      << "\n"
      // No cgroups, no accounting daemon, no systemd.
      << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
      << "JobAcctGatherType=jobacct_gather/none\nAccountingStorageType=accounting_storage/none\n"
      << "JobCompType=jobcomp/none\nMpiDefault=none\n"
      << "SlurmdParameters=config_overrides\n"
      // Else each wave of an array waits about 3 s.
      << "SchedulerParameters=batch_sched_delay=0\n"
      << "SelectType=select/cons_tres\nSelectTypeParameters=CR_CPU\n"
      << "ReturnToService=2\n"
      << "NodeName=efcnode NodeAddr=127.0.0.1 CPUs=2 RealMemory=1024 State=UNKNOWN\n"
      << "PartitionName=efc Nodes=efcnode Default=YES MaxTime=INFINITE State=UP\n";
    c.close();
    old_conf_ = std::getenv("SLURM_CONF") ? std::getenv("SLURM_CONF") : "";
    had_conf_ = std::getenv("SLURM_CONF") != nullptr;
    setenv("SLURM_CONF", conf.c_str(), 1);
    conf_set_ = true;
    ctld_ = spawn({find_program("slurmctld"), "-D", "-f", conf.string()}, dir_ / "slurmctld.out");
    slurmd_ = spawn({find_program("slurmd"), "-D", "-N", "efcnode", "-f", conf.string()}, dir_ / "slurmd.out");
    const bool up = wait_until(
        [&] {
          if (!alive(munged_) || !alive(ctld_) || !alive(slurmd_)) return true;
          const std::string state = shell_output(find_program("scontrol") + " -o show node efcnode");
          return state.find("State=IDLE") != std::string::npos;
        },
        30);
    if (!up || !alive(munged_) || !alive(ctld_) || !alive(slurmd_))
      return fail(why, "the cluster did not come up (node not idle in 30 s, or a daemon exited)");
    return true;
  }

  // A job to cancel before the daemons stop.
  void track_job(const std::string& id) { jobs_.push_back(id); }

  // Polls squeue until the job (every array task) has left the queue.
  bool wait_job(const std::string& id, double seconds) {
    return wait_until(
        [&] {
          int rc = 0;
          const std::string out = shell_output(find_program("squeue") + " -h -j " + id, &rc);
          return rc == 0 && out.find_first_not_of(" \n") == std::string::npos;
        },
        seconds);
  }

  // `scontrol -o show job ID`: one line per array task (no accounting
  // daemon, so this is where exit codes are).
  std::string show_job(const std::string& id) { return shell_output(find_program("scontrol") + " -o show job " + id); }

  // The daemons' own output, for a failure message.
  std::string logs() const {
    std::string out;
    for (const char* f : {"munged.out", "slurmctld.out", "slurmctld.log", "slurmd.out", "slurmd.log"}) {
      std::ifstream in(dir_ / f);
      std::stringstream ss;
      ss << in.rdbuf();
      std::string text = ss.str();
      if (text.size() > 3000) text = "..." + text.substr(text.size() - 3000);
      out += std::string("--- ") + f + "\n" + text;
    }
    return out;
  }

  void stop() {
    // Jobs first: their step daemons would outlive slurmd.
    if (alive(ctld_)) {
      for (const std::string& id : jobs_) shell_output(find_program("scancel") + " " + id);
      for (const std::string& id : jobs_) wait_job(id, 10);
    }
    jobs_.clear();
    for (pid_t* pid : {&slurmd_, &ctld_, &munged_}) end(pid);
    if (conf_set_) {
      if (had_conf_)
        setenv("SLURM_CONF", old_conf_.c_str(), 1);
      else
        unsetenv("SLURM_CONF");
      conf_set_ = false;
    }
    if (!dir_.empty() && std::getenv("EFC_KEEP_SLURM") == nullptr) {
      std::error_code ec;
      std::filesystem::remove_all(dir_, ec);
    }
    dir_.clear();
  }

 private:
  template <class Pred>
  static bool wait_until(Pred pred, double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      if (pred()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return pred();
  }

  bool fail(std::string* why, const std::string& message) {
    *why = message;
    return false;
  }

  // A daemon in the foreground, stdout and stderr into `log`.
  static pid_t spawn(const std::vector<std::string>& argv, const std::filesystem::path& log) {
    const pid_t pid = fork();
    if (pid == 0) {
      const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int null = open("/dev/null", O_RDONLY);
      dup2(null, 0);
      dup2(fd, 1);
      dup2(fd, 2);
      std::vector<char*> a;
      for (const std::string& s : argv) a.push_back(const_cast<char*>(s.c_str()));
      a.push_back(nullptr);
      execv(a[0], a.data());
      _exit(127);
    }
    return pid;
  }

  // Whether our child `pid` still runs (reaping it if it has ended).
  static bool alive(pid_t& pid) {
    if (pid <= 0) return false;
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) {
      pid = -pid;  // ended and reaped: never signalled again
      return false;
    }
    return true;
  }

  static void end(pid_t* pid) {
    if (!alive(*pid)) return;
    kill(*pid, SIGTERM);
    const bool gone = wait_until([&] { return !alive(*pid); }, 10);
    if (!gone && *pid > 0) {
      kill(*pid, SIGKILL);
      waitpid(*pid, nullptr, 0);
    }
    *pid = -1;
  }

  std::filesystem::path dir_;
  pid_t munged_ = -1, ctld_ = -1, slurmd_ = -1;
  std::vector<std::string> jobs_;
  std::string old_conf_;
  bool had_conf_ = false, conf_set_ = false;
};

}  // namespace efc_test
