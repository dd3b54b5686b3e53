#include "batch/runner.h"

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

#include "batch/atomic_file.h"
#include "batch/process.h"
#include "batch/record.h"

namespace efc::batch {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

namespace {

// What the signal handler needs: the running jobs' process groups, in slots
// it can read without locks, and the signal it got.
constexpr int kMaxParallel = 1024;
volatile sig_atomic_t g_groups[kMaxParallel];
volatile sig_atomic_t g_signal = 0;

extern "C" void on_signal(int sig) {
  // The first signal is passed on as it is; a second one (an impatient ^C)
  // kills the jobs outright.
  const int send = g_signal ? SIGKILL : sig;
  g_signal = sig;
  for (int i = 0; i < kMaxParallel; ++i)
    if (g_groups[i] > 0) kill(-static_cast<pid_t>(g_groups[i]), send);
}

// Installs on_signal for SIGINT, SIGTERM and SIGHUP while it lives, without
// SA_RESTART so that a blocked wait4 returns.
class SignalGuard {
 public:
  SignalGuard() {
    g_signal = 0;
    for (int i = 0; i < kMaxParallel; ++i) g_groups[i] = 0;
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    for (int k = 0; k < 3; ++k) sigaction(kSignals[k], &sa, &old_[k]);
  }
  ~SignalGuard() {
    for (int k = 0; k < 3; ++k) sigaction(kSignals[k], &old_[k], nullptr);
  }

 private:
  static constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGHUP};
  struct sigaction old_[3];
};

std::string host_name() {
  char buf[256] = {0};
  return gethostname(buf, sizeof buf - 1) == 0 ? std::string(buf) : std::string();
}

// The first `limit` bytes of a file (a job may print without end) and its size.
void read_head(const std::string& path, size_t limit, std::string* text, size_t* size) {
  std::error_code ec;
  const auto n = fs::file_size(path, ec);
  *size = ec ? 0 : static_cast<size_t>(n);
  std::ifstream in(path, std::ios::binary);
  text->assign(std::min(limit, *size), '\0');
  in.read(text->data(), static_cast<std::streamsize>(text->size()));
  text->resize(static_cast<size_t>(std::max<std::streamsize>(0, in.gcount())));
}

struct Running {
  size_t job = 0;  // index into the selection
  int slot = 0;
  Clock::time_point start;
  std::string started;
};

}  // namespace

bool write_results(const Layout& layout, const Shard& shard, const std::vector<json>& records, std::string* error) {
  std::string text;
  for (const json& r : records) text += record_line(r) + "\n";
  return write_file_atomically(layout.dir + "/" + results_name(shard), text, error);
}

int run_jobs(const RunOptions& opts, const std::vector<Job>& jobs, RunSummary* summary) {
  const Clock::time_point t0 = Clock::now();
  *summary = RunSummary{};
  summary->total = static_cast<int>(jobs.size());
  const std::string host = host_name();

  // What is done already: a complete record of this very job and command.
  std::vector<std::optional<json>> records(jobs.size());
  std::vector<size_t> pending;
  for (size_t i = 0; i < jobs.size(); ++i) {
    std::optional<json> r = read_record(opts.layout.record(jobs[i].id));
    if (r && record_matches(*r, jobs[i], opts.command) && !(opts.retry_failed && (*r)["exit_code"].get<int>() != 0)) {
      records[i] = std::move(r);
      ++summary->skipped;
    } else {
      pending.push_back(i);
    }
  }
  auto done_records = [&] {
    std::vector<json> out;
    for (const auto& r : records)
      if (r) out.push_back(*r);
    return out;
  };
  if (!write_results(opts.layout, opts.shard, done_records(), &summary->error)) return 2;

  SignalGuard guard;
  const int parallel = std::max(1, std::min(opts.parallel, kMaxParallel));
  std::map<pid_t, Running> running;
  std::vector<bool> slot_used(parallel, false);
  size_t next = 0;
  int done = summary->skipped;
  bool io_failed = false;
  Clock::time_point last_write = Clock::now();

  while (true) {
    // Start jobs while there is room, no signal came and nothing failed to write.
    while (!g_signal && !io_failed && next < pending.size() && static_cast<int>(running.size()) < parallel) {
      const size_t i = pending[next];
      const Job& job = jobs[i];
      const std::string job_dir = opts.layout.job_dir(job.id);
      // Forget the old result before touching the output it describes, then
      // clear what a killed run may have left half-written.
      std::error_code ec;
      fs::remove(opts.layout.record(job.id), ec);
      fs::remove_all(job_dir, ec);
      fs::create_directories(job_dir, ec);
      if (ec) {
        summary->error = "cannot create '" + job_dir + "': " + ec.message();
        io_failed = true;
        break;
      }
      SpawnOptions so;
      so.cwd = job_dir;
      so.stdout_file = opts.layout.job_stdout(job.id);
      so.stderr_file = opts.layout.job_stderr(job.id);
      std::string error;
      const std::vector<std::string> argv = job_argv(opts.efc_exe, opts.command, job, opts.kind, job_dir);
      Running r;
      r.job = i;
      r.started = utc_now();
      r.start = Clock::now();
      const pid_t pid = spawn(argv, so, &error);
      if (pid < 0) {
        summary->error = error;
        io_failed = true;
        break;
      }
      for (int s = 0; s < parallel; ++s)
        if (!slot_used[s]) {
          slot_used[s] = true;
          r.slot = s;
          break;
        }
      g_groups[r.slot] = pid;
      running[pid] = r;
      ++next;
      // A signal that came between fork and the slot being filled missed
      // this job: pass it on now.
      if (g_signal) kill(-pid, g_signal);
      if (opts.on_started) opts.on_started(job, done, summary->total, static_cast<int>(running.size()));
    }
    if (running.empty()) break;

    Exited ex;
    const int w = wait_any(&ex);
    if (w < 0) break;  // no child left (cannot happen while `running` holds one)
    if (w == 0) {
      // A signal: the handler has passed it on; wait for the jobs to end.
      if (g_signal)
        for (const auto& [pid, r] : running) kill(-pid, g_signal);
      continue;
    }
    const auto it = running.find(ex.pid);
    if (it == running.end()) continue;  // not a job (cannot happen: batch starts no other child here)
    const Running r = it->second;
    running.erase(it);
    g_groups[r.slot] = 0;
    slot_used[r.slot] = false;
    if (g_signal) {
      // Ended by the signal we passed on (or racing it): not a result.
      ++summary->unfinished;
      continue;
    }
    const Job& job = jobs[r.job];
    Outcome o;
    o.exit_code = ex.exit_code;
    o.signal = ex.signal;
    o.seconds = std::chrono::duration<double>(Clock::now() - r.start).count();
    o.peak_rss_mb = ex.peak_rss_mb;
    o.started = r.started;
    o.finished = utc_now();
    read_head(opts.layout.job_stderr(job.id), kDiagnosticsLimit, &o.diagnostics, &o.diagnostics_bytes);
    json record = make_record(job, opts.command, o, host);
    std::string error;
    if (!write_file_atomically(opts.layout.record(job.id),
                               record.dump(2, ' ', false, json::error_handler_t::replace) + "\n", &error)) {
      summary->error = error;
      io_failed = true;
      continue;
    }
    ++summary->ran;
    ++done;
    if (o.exit_code == 0)
      ++summary->ok;
    else
      ++summary->failed;
    records[r.job] = record;
    // The results file follows the records at most twice a second (rebuilding
    // it after each of thousands of short jobs would cost more than they do);
    // the records are what counts, and the file is rebuilt at the end.
    if (Clock::now() - last_write >= std::chrono::milliseconds(500)) {
      if (!write_results(opts.layout, opts.shard, done_records(), &error)) {
        summary->error = error;
        io_failed = true;
      }
      last_write = Clock::now();
    }
    if (opts.on_finished) opts.on_finished(record, done, summary->total);
  }

  summary->signal = g_signal;
  if (g_signal) summary->unfinished += static_cast<int>(pending.size() - next);
  for (const auto& r : records)
    if (r && (*r)["exit_code"].get<int>() != 0) summary->failures.push_back(*r);
  std::string error;
  if (!write_results(opts.layout, opts.shard, done_records(), &error) && summary->error.empty()) {
    summary->error = error;
    io_failed = true;
  }
  summary->seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  if (io_failed || summary->signal) return 2;
  return summary->failures.empty() ? 0 : 1;
}

}  // namespace efc::batch
