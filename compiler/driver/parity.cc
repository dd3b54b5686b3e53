// efc parity SPEC --profile P --duration S [--dt D] [--bullet-exe FILE] [--csv-dir DIR]
//
// Runs the MuJoCo harness (in process) and the compiled Bullet program over
// the same receptor trajectory and compares them per function.
//
// The same trajectory: the harness's receptors follow the profile through a
// servo (they lag it slightly), so the Bullet program is given the positions
// the harness realised (a csv: profile written at full precision) and
// prescribes them kinematically. s_E is then a function of identical inputs
// for every function whose receptor the profile moves, and must agree to
// float tolerance (1e-9 relative) on every row. A chained function's
// receptor is a geometry effector that each simulator moves with its own
// dynamics; its s_E must agree on every row where both simulators' s_E have
// held for 0.5 s, and switch the same number of times, each switch at most
// 0.05 s away from the harness's (the physics may move it; the largest shift
// is reported).
// Geometry effects: on rows where s_E has held for 0.5 s, the two measured
// joint positions differ by at most 2% of the effect's range.
// Exit: 0 parity holds, 1 it does not (or the spec is wrong), 2 usage, I/O
// or build failure.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "backends/bullet/bullet_backend.h"
#include "backends/common/lowering.h"
#include "compiler/core/load.h"
#include "compiler/driver/commands.h"
#include "harness/play.h"

namespace fs = std::filesystem;

namespace efc {
namespace {

constexpr double kSETolerance = 1e-9;  // relative
constexpr double kSteadyHold = 0.5;    // s
constexpr double kGeometryTolerance = 0.02;  // of the effect's range
constexpr double kChainShift = 0.05;   // s: the most a chained switch may move

struct TempDir {
  fs::path path;
  explicit TempDir(const fs::path& parent, const std::string& stem) {
    std::error_code ec;
    fs::create_directories(parent, ec);
    std::string tmpl = (parent / (stem + "-XXXXXX")).string();
    if (mkdtemp(tmpl.data())) path = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    if (!path.empty()) fs::remove_all(path, ec);
  }
};

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

// FNV-1a over every emitted file (path and content): the cache key.
std::string hash_tree(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  uint64_t h = 1469598103934665603ull;
  auto feed = [&](const std::string& s) {
    for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
    h = (h ^ 0xff) * 1099511628211ull;
  };
  for (const fs::path& f : files) {
    feed(fs::relative(f, dir).string());
    feed(read_text(f));
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

fs::path cache_root() {
  const char* t = std::getenv("TMPDIR");
  return fs::path(t && *t ? t : "/tmp") / "efc-parity-cache";
}

// Emits the Bullet target and builds it (cmake), reusing a build of the same
// sources. Returns the program's path, or "" after printing why.
std::string build_bullet(const Object& obj, Diagnostics& diags) {
  const fs::path root = cache_root();
  TempDir staging(root, "staging");
  if (staging.path.empty()) {
    std::cerr << "efc parity: cannot create a folder under " << root << "\n";
    return "";
  }
  const fs::path src = staging.path / "src";
  fs::create_directories(src);
  std::vector<OutputFile> files;
  if (!generate_bullet_target(obj, diags, &files) || !write_output_files(src.string(), files, diags))
    return "";
  const std::string key = obj.name + "-" + hash_tree(src);
  const fs::path dest = root / key;
  const fs::path exe = dest / "build" / (obj.name + "_bullet");
  if (access(exe.c_str(), X_OK) == 0) {
    std::cerr << "parity: reusing the Bullet build in " << dest.string() << "\n";
    return exe.string();
  }
  std::cerr << "parity: building the Bullet program in " << dest.string()
            << " (cmake; cached for the next run)\n";
  const fs::path build = staging.path / "build";
  const fs::path log = staging.path / "build.log";
  const std::string quiet = " >>" + shell_quote(log.string()) + " 2>&1";
  std::cerr << "parity: configuring...\n";
  if (run_command("cmake -S " + shell_quote(src.string()) + " -B " + shell_quote(build.string()) +
                  " -DCMAKE_BUILD_TYPE=Release" + quiet) != 0) {
    std::cerr << "efc parity: cmake could not configure the Bullet program:\n"
              << tail(read_text(log), 3000) << "\n";
    return "";
  }
  std::cerr << "parity: compiling...\n";
  if (run_command("cmake --build " + shell_quote(build.string()) + " -j2" + quiet) != 0) {
    std::cerr << "efc parity: the Bullet program did not build:\n" << tail(read_text(log), 3000) << "\n";
    return "";
  }
  std::error_code ec;
  fs::rename(staging.path, dest, ec);  // atomic publish; a concurrent twin may have won
  if (access(exe.c_str(), X_OK) != 0) {
    std::cerr << "efc parity: the Bullet build vanished from " << dest.string() << "\n";
    return "";
  }
  if (!ec) staging.path.clear();
  return exe.string();
}

bool read_csv(const std::string& path, std::vector<std::string>* header,
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

// Index of the first row of the run of equal values that ends at row i.
std::vector<size_t> hold_start(const std::vector<double>& v) {
  std::vector<size_t> out(v.size(), 0);
  for (size_t i = 1; i < v.size(); ++i) out[i] = v[i] == v[i - 1] ? out[i - 1] : i;
  return out;
}

std::vector<size_t> transitions(const std::vector<double>& v) {
  std::vector<size_t> out;
  for (size_t i = 1; i < v.size(); ++i)
    if (v[i] != v[i - 1]) out.push_back(i);
  return out;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

int cmd_parity(const std::string& spec, const std::string& profile_text, double duration, double dt,
               const std::string& bullet_exe, const std::string& csv_dir, const CommonOptions& common) {
  Diagnostics diags;
  auto finish = [&](int rc) {
    diags.print(std::cerr, common.json_diagnostics);
    return rc;
  };
  if (!check_timing("efc parity", duration, dt)) return 2;
  PlayOptions opts;
  std::string error;
  int line = 0;
  bool io = false;
  if (!parse_profile(profile_text, &opts.profile, &error, &line, &io)) {
    std::cerr << "efc parity: " << error << "\n";
    return io || line == 0 ? 2 : 1;
  }
  LoadOptions load_opts;
  load_opts.allow_absolute_paths = common.allow_absolute_paths;
  bool io_error = false;
  std::optional<Object> obj = load_spec(spec, load_opts, diags, &io_error);
  if (!obj) return finish(io_error ? 2 : 1);

  std::string exe = bullet_exe;
  if (exe.empty()) {
    Diagnostics build_diags;  // the target's W0900s are the compiler's business, not parity's
    exe = build_bullet(*obj, build_diags);
    if (exe.empty()) {
      build_diags.print(std::cerr, common.json_diagnostics);
      return finish(2);
    }
  } else if (access(exe.c_str(), X_OK) != 0) {
    std::cerr << "efc parity: cannot run '" << exe << "'\n";
    return 2;
  }

  // The MuJoCo harness, in process.
  opts.duration = duration;
  opts.dt = dt;
  PlayLog log;
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = play(*obj, opts, diags, &log);
  const double mujoco_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (rc != 0) return finish(rc);

  // The receptor trajectory the harness realised, at full precision.
  TempDir work(fs::temp_directory_path(), "efc-parity");
  if (work.path.empty()) {
    std::cerr << "efc parity: cannot create a temporary folder\n";
    return finish(2);
  }
  const std::vector<int> driven = lowering::profile_driven_receptors(*obj);
  std::vector<size_t> driven_col;
  for (int part : driven) {
    size_t col = 0;
    for (const Function& f : obj->functions)
      if (f.receptor_index == part && !col)
        col = std::find(log.columns.begin(), log.columns.end(), f.name + ".s_R") - log.columns.begin();
    driven_col.push_back(col);
  }
  const fs::path traj = work.path / "receptors.csv";
  {
    std::ofstream out(traj);
    out << "t";
    for (int part : driven) out << "," << obj->parts[part].name;
    out << "\n";
    char buf[40];
    for (const auto& row : log.rows) {
      std::snprintf(buf, sizeof buf, "%.17g", row[0]);
      out << buf;
      for (size_t c : driven_col) {
        std::snprintf(buf, sizeof buf, "%.17g", row[c]);
        out << "," << buf;
      }
      out << "\n";
    }
    if (!out) {
      std::cerr << "efc parity: cannot write " << traj << "\n";
      return finish(2);
    }
  }
  const fs::path bcsv = work.path / "bullet.csv", berr = work.path / "bullet.err";
  char num[128];
  std::string cmd = shell_quote(exe) + " --profile " + shell_quote("csv:" + traj.string());
  std::snprintf(num, sizeof num, " --duration %.17g --dt %.17g", duration, dt);
  cmd += num;
  cmd += " --precision 17 --quiet --csv " + shell_quote(bcsv.string()) + " 2>" + shell_quote(berr.string());
  const int brc = run_command(cmd);
  const std::string bstderr = read_text(berr);
  if (brc != 0) {
    std::cerr << "efc parity: the Bullet program failed (exit " << brc << "):\n" << tail(bstderr, 3000);
    return finish(2);
  }
  std::vector<std::string> header;
  std::vector<std::vector<double>> brows;
  if (!read_csv(bcsv.string(), &header, &brows)) {
    std::cerr << "efc parity: cannot read the Bullet program's CSV\n";
    return finish(2);
  }
  if (header != log.columns || brows.size() != log.rows.size()) {
    std::cerr << "efc parity: the Bullet CSV has other columns or rows than the harness's ("
              << header.size() << " columns x " << brows.size() << " rows, want " << log.columns.size()
              << " x " << log.rows.size() << ")\n";
    return finish(1);
  }
  if (!csv_dir.empty()) {
    std::error_code ec;
    fs::create_directories(csv_dir, ec);
    std::string werr;
    if (ec || !write_log_csv(log, (fs::path(csv_dir) / "mujoco.csv").string(), &werr)) {
      std::cerr << "efc parity: cannot write into " << csv_dir << "\n";
      return finish(2);
    }
    fs::copy_file(bcsv, fs::path(csv_dir) / "bullet.csv", fs::copy_options::overwrite_existing, ec);
    fs::copy_file(traj, fs::path(csv_dir) / "receptors.csv", fs::copy_options::overwrite_existing, ec);
  }

  std::set<int> geometry_effectors;
  for (const Function& f : obj->functions)
    if (f.effect.type == EffectType::Geometry) geometry_effectors.insert(f.effector_index);

  bool all_ok = true;
  std::printf("parity: %s, profile %s, %g s at dt %g (%zu rows)\n", obj->name.c_str(),
              profile_text.c_str(), duration, dt, log.rows.size());
  std::printf("%-18s %-12s %-7s %-10s %-10s %-12s %-14s %s\n", "function", "effect", "input",
              "max|dsR|", "max|dsE|", "max|dmeas|", "steady/range", "result");
  const size_t hold_rows = static_cast<size_t>(std::lround(kSteadyHold / dt));
  for (size_t c = 1; c + 2 < log.columns.size(); c += 3) {
    const std::string fname = log.columns[c].substr(0, log.columns[c].size() - 4);
    const Function* f = nullptr;
    for (const Function& g : obj->functions)
      if (g.name == fname) f = &g;
    if (!f) continue;
    const bool chained = geometry_effectors.count(f->receptor_index) > 0;
    std::vector<double> me, be;
    double d_sr = 0, d_se = 0, d_meas = 0, steady = 0;
    bool se_ok = true;
    for (size_t r = 0; r < brows.size(); ++r) {
      const auto& a = log.rows[r];
      const auto& b = brows[r];
      me.push_back(a[c + 1]);
      be.push_back(b[c + 1]);
      d_sr = std::max(d_sr, std::fabs(a[c] - b[c]));
      const double dse = std::fabs(a[c + 1] - b[c + 1]);
      d_se = std::max(d_se, dse);
      d_meas = std::max(d_meas, std::fabs(a[c + 2] - b[c + 2]));
      if (!chained && dse > kSETolerance * (1 + std::fabs(a[c + 1]))) se_ok = false;
    }
    std::string note;
    const std::vector<size_t> hm = hold_start(me), hb = hold_start(be);
    if (chained) {
      const std::vector<size_t> tm = transitions(me), tb = transitions(be);
      if (tm.size() != tb.size()) {
        se_ok = false;
        note = " (" + std::to_string(tm.size()) + " vs " + std::to_string(tb.size()) + " switches)";
      } else {
        size_t shift = 0;
        for (size_t i = 0; i < tm.size(); ++i) shift = std::max(shift, tm[i] > tb[i] ? tm[i] - tb[i] : tb[i] - tm[i]);
        note = " (chained: switches shifted <= " + fmt(shift * dt) + " s)";
        if (shift * dt > kChainShift + 1e-12) se_ok = false;
      }
      for (size_t r = 0; r < me.size(); ++r)
        if (r - hm[r] >= hold_rows && r - hb[r] >= hold_rows &&
            std::fabs(me[r] - be[r]) > kSETolerance * (1 + std::fabs(me[r])))
          se_ok = false;
    }
    bool geo_ok = true;
    std::string steady_text = "-";
    if (f->effect.type == EffectType::Geometry) {
      const double span = std::fabs(f->effect.hi - f->effect.lo);
      for (size_t r = 0; r < me.size(); ++r)
        if (r - hm[r] >= hold_rows)
          steady = std::max(steady, std::fabs(log.rows[r][c + 2] - brows[r][c + 2]) / span);
      geo_ok = steady <= kGeometryTolerance;
      steady_text = fmt(100 * steady) + "%";
    }
    const bool ok = se_ok && geo_ok;
    all_ok = all_ok && ok;
    std::printf("%-18s %-12s %-7s %-10s %-10s %-12s %-14s %s%s\n", fname.c_str(),
                to_string(f->effect.type), chained ? "chain" : "profile", fmt(d_sr).c_str(),
                fmt(d_se).c_str(), fmt(d_meas).c_str(), steady_text.c_str(),
                ok ? "ok" : (!se_ok ? "FAIL s_E" : "FAIL measured"), note.c_str());
  }
  // Speed: the harness's loop (MuJoCo + runtime + logging) and Bullet's.
  const size_t at = bstderr.rfind("steps/s");
  double bullet_sps = 0;
  if (at != std::string::npos) {
    const size_t open = bstderr.rfind('(', at);
    if (open != std::string::npos) bullet_sps = std::strtod(bstderr.c_str() + open + 1, nullptr);
  }
  const double steps = static_cast<double>(log.rows.size() - 1);
  std::printf("speed: MuJoCo harness %.0f steps/s, Bullet %.0f steps/s\n",
              mujoco_s > 0 ? steps / mujoco_s : 0.0, bullet_sps);
  std::printf("parity: %s\n", all_ok ? "holds" : "FAILS");
  std::fflush(stdout);
  return finish(all_ok ? 0 : 1);
}

}  // namespace efc
