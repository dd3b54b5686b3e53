#include "eval/bullet_program.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "backends/bullet/bullet_backend.h"
#include "backends/common/temp_dir.h"

namespace fs = std::filesystem;

namespace efc {
namespace {

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

int run_command(const std::string& cmd) {
  const int st = std::system(cmd.c_str());
  if (st == -1) return -1;
  if (WIFEXITED(st)) return WEXITSTATUS(st);
  return 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string tail(const std::string& s, size_t n) { return s.size() > n ? s.substr(s.size() - n) : s; }

// FNV-1a over every file (path and content): the cache key.
std::string hash_files(const std::vector<OutputFile>& files) {
  std::vector<const OutputFile*> sorted;
  for (const OutputFile& f : files) sorted.push_back(&f);
  std::sort(sorted.begin(), sorted.end(), [](auto* a, auto* b) { return a->path < b->path; });
  uint64_t h = 1469598103934665603ull;
  auto feed = [&](const std::string& s) {
    for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
    h = (h ^ 0xff) * 1099511628211ull;
  };
  for (const OutputFile* f : sorted) {
    feed(f->path);
    feed(f->bytes);
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

fs::path cache_root() {
  const char* t = std::getenv("TMPDIR");
  return fs::path(t && *t ? t : "/tmp") / "efc-parity-cache";
}

}  // namespace

std::string build_bullet_program(const Object& obj, Diagnostics& diags, const ProgressFn& progress) {
  std::vector<OutputFile> files;
  if (!generate_bullet_target(obj, diags, &files)) return "";
  const fs::path root = cache_root();
  const std::string key = obj.name + "-" + hash_files(files);
  const fs::path dest = root / key;
  const fs::path exe = dest / "build" / (obj.name + "_bullet");
  if (access(exe.c_str(), X_OK) == 0) {
    progress("parity: reusing the Bullet build in " + dest.string());
    return exe.string();
  }
  TempDir staging(root, "staging");
  if (staging.path().empty()) {
    diags.error("E0900", root.string(), 0, 0, "", "cannot create a folder under " + root.string());
    return "";
  }
  const fs::path src = staging.path() / "src";
  fs::create_directories(src);
  if (!write_output_files(src.string(), files, diags)) return "";
  progress("parity: building the Bullet program in " + dest.string() + " (cmake; cached for the next run)");
  const fs::path build = staging.path() / "build";
  const fs::path log = staging.path() / "build.log";
  const std::string quiet = " >>" + shell_quote(log.string()) + " 2>&1";
  progress("parity: configuring...");
  if (run_command("cmake -S " + shell_quote(src.string()) + " -B " + shell_quote(build.string()) +
                  " -DCMAKE_BUILD_TYPE=Release" + quiet) != 0) {
    diags.error("E0913", "", 0, 0, "",
                "cmake could not configure the Bullet program:\n" + tail(read_text(log), 3000));
    return "";
  }
  progress("parity: compiling...");
  if (run_command("cmake --build " + shell_quote(build.string()) + " -j2" + quiet) != 0) {
    diags.error("E0913", "", 0, 0, "", "the Bullet program did not build:\n" + tail(read_text(log), 3000));
    return "";
  }
  std::error_code ec;
  fs::rename(staging.path(), dest, ec);  // atomic publish; a concurrent twin may have won
  if (access(exe.c_str(), X_OK) != 0) {
    diags.error("E0913", "", 0, 0, "", "the Bullet build vanished from " + dest.string());
    return "";
  }
  if (!ec) staging.release();
  return exe.string();
}

bool read_numeric_csv(const std::string& path, std::vector<std::string>* header,
                      std::vector<std::vector<double>>* rows) {
  std::ifstream in(path);
  if (!in) return false;
  std::string line;
  if (!std::getline(in, line)) return false;
  std::stringstream hs(line);
  std::string cell;
  while (std::getline(hs, cell, ',')) header->push_back(cell);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<double> row;
    std::stringstream ss(line);
    while (std::getline(ss, cell, ',')) row.push_back(std::strtod(cell.c_str(), nullptr));
    rows->push_back(std::move(row));
  }
  return true;
}

bool run_bullet_program(const std::string& exe, const std::string& trajectory_csv, double duration,
                        double dt, const std::string& work_dir, Diagnostics& diags,
                        std::vector<std::string>* header, std::vector<std::vector<double>>* rows,
                        double* steps_per_second) {
  const fs::path csv = fs::path(work_dir) / "bullet.csv", err = fs::path(work_dir) / "bullet.err";
  char num[128];
  std::string cmd = shell_quote(exe) + " --profile " + shell_quote("csv:" + trajectory_csv);
  std::snprintf(num, sizeof num, " --duration %.17g --dt %.17g", duration, dt);
  cmd += num;
  cmd += " --precision 17 --quiet --csv " + shell_quote(csv.string()) + " 2>" + shell_quote(err.string());
  const int rc = run_command(cmd);
  const std::string stderr_text = read_text(err);
  if (rc != 0) {
    diags.error("E0913", "", 0, 0, "",
                "the Bullet program failed (exit " + std::to_string(rc) + "):\n" + tail(stderr_text, 3000));
    return false;
  }
  if (!read_numeric_csv(csv.string(), header, rows)) {
    diags.error("E0913", "", 0, 0, "", "cannot read the Bullet program's CSV");
    return false;
  }
  // Speed: the program's last stderr line ends "(N steps/s)".
  *steps_per_second = 0;
  const size_t at = stderr_text.rfind("steps/s");
  if (at != std::string::npos) {
    const size_t open = stderr_text.rfind('(', at);
    if (open != std::string::npos) *steps_per_second = std::strtod(stderr_text.c_str() + open + 1, nullptr);
  }
  return true;
}

}  // namespace efc
