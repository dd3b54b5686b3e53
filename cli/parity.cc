// efc parity SPEC --profile P --duration S [--dt D] [--bullet-exe FILE] [--csv-dir DIR]
//
// Runs the MuJoCo harness (in process) and the compiled Bullet program over
// the same receptor trajectory and compares them per function (the metric:
// eval/parity.h). Prints a table on stdout.
// Exit: 0 parity holds, 1 it does not (or the spec is wrong), 2 usage, I/O
// or build failure.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "backends/common/lowering.h"
#include "backends/common/temp_dir.h"
#include "cli/commands.h"
#include "eval/bullet_program.h"
#include "eval/parity.h"
#include "harness/play.h"

namespace fs = std::filesystem;

namespace efc {
namespace {

std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// The receptor trajectory the harness realised, at full precision: the
// Bullet program's csv: profile.
bool write_trajectory(const Object& obj, const PlayLog& log, const fs::path& path) {
  const std::vector<int> driven = lowering::profile_driven_receptors(obj);
  std::vector<size_t> driven_col;
  for (int part : driven) {
    size_t col = 0;
    for (const Function& f : obj.functions)
      if (lowering::receptor_part(obj, f) == part && !col)
        col = std::find(log.columns.begin(), log.columns.end(), f.name + ".s_R") - log.columns.begin();
    driven_col.push_back(col);
  }
  std::ofstream out(path);
  out << "t";
  for (int part : driven) out << "," << obj.parts[part].name;
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
  return static_cast<bool>(out);
}

void print_table(const Object& obj, const ParityArgs& args, size_t rows,
                 const std::vector<FunctionParity>& result, double mujoco_sps, double bullet_sps,
                 bool all_ok) {
  std::printf("parity: %s, profile %s, %g s at dt %g (%zu rows)\n", obj.name.c_str(), args.profile.c_str(),
              args.duration, args.dt, rows);
  std::printf("%-18s %-12s %-7s %-10s %-10s %-12s %-14s %s\n", "function", "effect", "input", "max|dsR|",
              "max|dsE|", "max|dmeas|", "steady/range", "result");
  for (const FunctionParity& p : result) {
    const std::string steady = p.steady_fraction < 0 ? "-" : short_number(100 * p.steady_fraction) + "%";
    std::printf("%-18s %-12s %-7s %-10s %-10s %-12s %-14s %s%s\n", p.function.c_str(), to_string(p.effect),
                p.chained ? "chain" : "profile", short_number(p.max_ds_r).c_str(),
                short_number(p.max_ds_e).c_str(), short_number(p.max_dmeasured).c_str(), steady.c_str(),
                p.ok() ? "ok" : (!p.se_ok ? "FAIL s_E" : "FAIL measured"), p.note.c_str());
  }
  std::printf("speed: MuJoCo harness %.0f steps/s, Bullet %.0f steps/s\n", mujoco_sps, bullet_sps);
  std::printf("parity: %s\n", all_ok ? "holds" : "FAILS");
  std::fflush(stdout);
}

}  // namespace

int cmd_parity(Report& report, const ParityArgs& args) {
  PlayOptions opts;
  int rc = kExitOk;
  std::optional<Object> obj = load_for_run(report, args.spec, args.profile, args.duration, args.dt, &opts.profile, &rc);
  if (!obj) return rc;

  std::string exe = args.bullet_exe;
  const auto progress = [&report](const std::string& line) { report.note(line); };
  if (exe.empty()) {
    Diagnostics build_diags;  // the target's W0900s are the compiler's business, not parity's
    exe = build_bullet_program(*obj, build_diags, progress);
    if (exe.empty()) {
      for (const Diagnostic& d : build_diags.items())
        if (d.severity == Severity::Error) report.diags().add(d);
      report.flush();
      return kExitUsage;
    }
  } else if (access(exe.c_str(), X_OK) != 0) {
    return report.fail("E0910", "cannot run '" + exe + "'", kExitUsage);
  }

  // The MuJoCo harness, in process.
  opts.duration = args.duration;
  opts.dt = args.dt;
  PlayLog log;
  const auto t0 = std::chrono::steady_clock::now();
  rc = play(*obj, opts, report.diags(), &log);
  const double mujoco_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  report.flush();
  if (rc != kExitOk) return rc;

  TempDir work("efc-parity");
  if (work.path().empty()) return report.fail("E0900", "cannot create a temporary folder", kExitUsage);
  const fs::path traj = work.path() / "receptors.csv";
  if (!write_trajectory(*obj, log, traj))
    return report.fail("E0900", "cannot write " + traj.string(), kExitUsage);
  SimLog bullet;
  double bullet_sps = 0;
  if (!run_bullet_program(exe, traj.string(), args.duration, args.dt, work.path().string(), report.diags(),
                          &bullet.columns, &bullet.rows, &bullet_sps)) {
    report.flush();
    return kExitUsage;
  }
  if (!args.csv_dir.empty()) {
    std::error_code ec;
    fs::create_directories(args.csv_dir, ec);
    std::string error;
    if (ec || !write_log_csv(log, (fs::path(args.csv_dir) / "mujoco.csv").string(), &error))
      return report.fail("E0900", "cannot write into " + args.csv_dir, kExitUsage);
    fs::copy_file(work.path() / "bullet.csv", fs::path(args.csv_dir) / "bullet.csv",
                  fs::copy_options::overwrite_existing, ec);
    fs::copy_file(traj, fs::path(args.csv_dir) / "receptors.csv", fs::copy_options::overwrite_existing, ec);
  }

  std::string error;
  const std::vector<FunctionParity> result =
      compare_logs(*obj, SimLog{log.columns, log.rows}, bullet, args.dt, &error);
  if (!error.empty()) return report.fail("E0912", "the Bullet CSV does not match the harness's: " + error, kExitBadInput);
  bool all_ok = true;
  for (const FunctionParity& p : result) all_ok = all_ok && p.ok();
  const double steps = static_cast<double>(log.rows.size() - 1);
  print_table(*obj, args, log.rows.size(), result, mujoco_s > 0 ? steps / mujoco_s : 0.0, bullet_sps, all_ok);
  if (!all_ok) {
    std::string failing;
    for (const FunctionParity& p : result)
      if (!p.ok()) failing += (failing.empty() ? "" : ", ") + p.function;
    return report.fail("E0912", "parity fails for " + failing + " (see the table on stdout)", kExitBadInput);
  }
  return kExitOk;
}

}  // namespace efc
