// First call in a fresh process (bench/README.md): what one `efc compile`
// costs, set against what one program that loads the result in MuJoCo costs.
//
// compile_bench repeats each call thousands of times in one process, which
// measures the steady state: caches warm, MuJoCo's one-time set-up paid long
// ago. But `efc compile` is a command run once, and a simulation loads its
// model once. Here every measurement is a new process (this program re-run
// with --one), timing the first call only, after process start-up:
//   compile  efc::load_spec + the mujoco backend's emit into a new folder
//            (compile_bench's compile_mujoco, minus the loop)
//   load     mj_loadXML of the emitted XML
// The two alternate, 15 of each per spec (--runs N), and the median is kept.
//
//   first_call_bench [--runs N] [--json FILE]    every spec of bench_specs()
//   first_call_bench --one compile SPEC DIR     one child: prints "cpu_ms wall_ms"
//   first_call_bench --one load XML             one child: prints "cpu_ms wall_ms"
#include <mujoco/mujoco.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "bench/bench_common.h"
#include "compiler/core/load.h"
#include "harness/mujoco_errors.h"

namespace fs = std::filesystem;

namespace {

double now_ms(clockid_t clock) {
  timespec t;
  clock_gettime(clock, &t);
  return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

// The child: one call, timed; prints "cpu_ms wall_ms" on stdout.
int run_one(int argc, char** argv) {
  efc::install_mujoco_handlers();
  const std::string what = argc > 2 ? argv[2] : "";
  const double cpu0 = now_ms(CLOCK_PROCESS_CPUTIME_ID), wall0 = now_ms(CLOCK_MONOTONIC);
  bool ok = false;
  std::string error;
  mjModel* model = nullptr;  // freed after the clock is read
  try {
    if (what == "compile" && argc == 5) {
      std::error_code ec;
      fs::create_directory(argv[4], ec);
      efc::Diagnostics diags;
      auto obj = efc::load_spec(argv[3], efc::LoadOptions{}, diags);
      ok = obj && efc::find_backend("mujoco")->emit(*obj, argv[4], diags);
      if (!ok) error = "compile failed";
    } else if (what == "load" && argc == 4) {
      char load_error[1024] = "";
      model = mj_loadXML(argv[3], nullptr, load_error, sizeof load_error);
      ok = model != nullptr;
      if (!ok) error = load_error;
    } else {
      error = "usage: first_call_bench --one compile SPEC DIR | --one load XML";
    }
  } catch (const std::exception& e) {
    error = e.what();
  }
  const double cpu = now_ms(CLOCK_PROCESS_CPUTIME_ID) - cpu0, wall = now_ms(CLOCK_MONOTONIC) - wall0;
  if (model) mj_deleteModel(model);
  if (!ok) {
    std::fprintf(stderr, "first_call_bench: %s\n", error.c_str());
    return 1;
  }
  std::printf("%.6f %.6f\n", cpu, wall);
  return 0;
}

struct Timing {
  double cpu_ms = 0, wall_ms = 0;
};

// Runs this program again with `args` and reads its "cpu_ms wall_ms".
bool run_child(const std::vector<std::string>& args, Timing* out, std::string* error) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) return *error = "pipe failed", false;
  const pid_t pid = fork();
  if (pid < 0) return *error = "fork failed", false;
  if (pid == 0) {
    dup2(pipe_fds[1], STDOUT_FILENO);
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv("/proc/self/exe", argv.data());
    _exit(127);
  }
  close(pipe_fds[1]);
  std::string text;
  char buf[256];
  ssize_t n;
  while ((n = read(pipe_fds[0], buf, sizeof buf)) > 0) text.append(buf, static_cast<size_t>(n));
  close(pipe_fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 ||
      std::sscanf(text.c_str(), "%lf %lf", &out->cpu_ms, &out->wall_ms) != 2) {
    *error = "child '" + args[2] + " " + args[3] + "' failed (see its message above)";
    return false;
  }
  return true;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "--one") == 0) return run_one(argc, argv);
  int runs = 15;
  std::string json_path;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--json" && i + 1 < argc) {
      json_path = argv[++i];
    } else {
      std::fprintf(stderr, "usage: first_call_bench [--runs N] [--json FILE]\n");
      return 2;
    }
  }
  efc::install_mujoco_handlers();
  efc_bench::TempDir tmp("efc-bench-first-call");
  std::string json = "{\"runs\": " + std::to_string(runs) + ", \"specs\": [";
  std::printf("First call in a fresh process (%d processes per figure, median; CPU ms)\n", runs);
  std::printf("%-22s %10s %12s %8s %14s %14s\n", "spec", "compile", "mujoco load", "ratio",
              "compile wall", "load wall");
  int status = 0;
  bool first = true;
  for (const efc_bench::BenchSpec& spec : efc_bench::bench_specs()) {
    // The XML every load child reads: one compile beforehand.
    std::string error;
    const auto obj = efc_bench::load(spec.path, &error);
    const fs::path ref = tmp.path() / (spec.name + "-ref");
    fs::create_directory(ref);
    efc::Diagnostics diags;
    if (!obj || !efc::find_backend("mujoco")->emit(*obj, ref.string(), diags)) {
      std::fprintf(stderr, "first_call_bench: cannot compile %s: %s\n", spec.path.c_str(), error.c_str());
      status = 1;
      continue;
    }
    const std::string xml = (ref / (obj->name + ".xml")).string();
    std::vector<double> c_cpu, c_wall, l_cpu, l_wall;
    for (int r = 0; r < runs && error.empty(); ++r) {
      const std::string out = (tmp.path() / (spec.name + "-" + std::to_string(r))).string();
      Timing c, l;
      // Alternate which goes first, so neither always follows the other.
      const bool compile_first = r % 2 == 0;
      for (int k = 0; k < 2 && error.empty(); ++k) {
        if ((k == 0) == compile_first) {
          if (run_child({argv[0], "--one", "compile", spec.path, out}, &c, &error))
            c_cpu.push_back(c.cpu_ms), c_wall.push_back(c.wall_ms);
        } else if (run_child({argv[0], "--one", "load", xml}, &l, &error)) {
          l_cpu.push_back(l.cpu_ms), l_wall.push_back(l.wall_ms);
        }
      }
      std::error_code ec;
      fs::remove_all(out, ec);
    }
    if (!error.empty()) {
      std::fprintf(stderr, "first_call_bench: %s: %s\n", spec.name.c_str(), error.c_str());
      status = 1;
      continue;
    }
    const double cc = median(c_cpu), lc = median(l_cpu), cw = median(c_wall), lw = median(l_wall);
    std::printf("%-22s %10.3f %12.3f %8.2f %14.3f %14.3f\n", spec.name.c_str(), cc, lc, cc / lc, cw,
                lw);
    std::fflush(stdout);
    char row[512];
    std::snprintf(row, sizeof row,
                  "%s{\"spec\": \"%s\", \"parts\": %zu, \"compile_cpu_ms\": %.6f, "
                  "\"load_cpu_ms\": %.6f, \"compile_wall_ms\": %.6f, \"load_wall_ms\": %.6f}",
                  first ? "" : ", ", spec.name.c_str(), obj->parts.size(), cc, lc, cw, lw);
    json += row;
    first = false;
  }
  json += "]}\n";
  if (!json_path.empty()) std::ofstream(json_path) << json;
  return status;
}
