// The Bullet target: every example emits, builds against the system Bullet
// (bullet-float64), passes its frame self-check, and its program's CSV passes
// the harness's semantic checks (s_E from the spec's formula, effects
// realised) under every profile; `efc parity` holds for every example and
// every profile (through the CLI), and once with its own cached cmake build.
//
// Each program is built once (g++, two at a time, runtime objects shared) and
// run for every profile, to keep the suite to a few minutes on two cores.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "backends/common/lowering.h"
#include "backends/mujoco/mujoco_backend.h"
#include "compiler/core/load.h"
#include "compiler/core/resolve.h"
#include "efc_profile.h"
#include "harness/play.h"
#include "spec_formula.h"
#include "tests/process_temp_dir.h"

namespace fs = std::filesystem;
using namespace efc;

namespace {

const char* kProfiles[] = {"ramp", "sweep", "press:3", "hold:hi", "hold:lo"};
constexpr double kDuration = 4.0, kDt = 0.002;
const std::string kEfc = std::string(EFC_BINARY_DIR) + "/efc";

std::vector<std::string> example_files() {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(fs::path(EFC_SOURCE_DIR) / "examples"))
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

int sh(const std::string& cmd) {
  const int st = std::system(cmd.c_str());
  return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Built {
  std::string name, spec, dir, exe, compile_log;
  std::vector<std::string> warnings;
  bool emitted = false, built = false;
};

// Emits and builds every example once for the whole suite.
class Programs {
 public:
  static Programs& get() {
    static Programs p;
    return p;
  }
  std::map<std::string, Built> by_name;
  fs::path root;
  std::string setup_error;

 private:
  Programs() {
    root = temp_.path();
    fs::create_directories(root);
    const Backend* bullet = find_backend("bullet");
    if (!bullet) {
      setup_error = "no bullet backend registered";
      return;
    }
    for (const std::string& file : example_files()) {
      Built b;
      b.spec = file;
      Diagnostics diags;
      auto obj = load_spec(file, {}, diags);
      if (!obj) continue;
      b.name = obj->name;
      b.dir = (root / b.name).string();
      fs::create_directories(b.dir);
      b.emitted = bullet->emit(*obj, b.dir, diags);
      for (const auto& d : diags.items()) b.warnings.push_back(d.code + ": " + d.message);
      b.exe = (root / b.name).string() + "/" + b.name + "_bullet";
      by_name[b.name] = b;
    }
    // The runtime and profile sources are the same in every folder: compile once.
    const std::string flags = "-std=c++17 -O2 $(pkg-config --cflags bullet-float64)";
    const std::string any = by_name.empty() ? "" : by_name.begin()->second.dir;
    if (any.empty() ||
        sh("g++ " + flags + " -c " + any + "/efc_runtime/efc_runtime.cc -o " + (root / "rt.o").string()) ||
        sh("g++ " + flags + " -c " + any + "/efc_runtime/efc_profile.cc -o " + (root / "pr.o").string())) {
      setup_error = "cannot compile the copied runtime sources";
      return;
    }
    flags_ = flags;
  }
  std::string flags_;
  // Every member is made before the constructor runs: the folder exists by then.
  const efc_test::ProcessTempDir temp_{"efc-bullet-test-"};

 public:
  // Builds one example's program the first time a test needs it: under CTest
  // every test is its own process, so building all of them up front would
  // repeat 19 builds per test.
  Built& require(const std::string& name) {
    Built& b = by_name[name];
    if (b.emitted && !b.built && b.compile_log.empty()) {
      const std::string log = b.dir + "/compile.log";
      b.built = sh("g++ " + flags_ + " -I" + b.dir + " " + b.dir + "/" + b.name + "_bullet.cc " +
                   (root / "rt.o").string() + " " + (root / "pr.o").string() +
                   " $(pkg-config --libs bullet-float64) -o " + b.exe + " >" + log + " 2>&1") == 0;
      b.compile_log = read_text(log);
      if (b.compile_log.empty()) b.compile_log = " ";  // built once, even when silent
    }
    return b;
  }
};

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
};

bool read_csv(const std::string& path, Csv* out) {
  std::ifstream in(path);
  std::string line, cell;
  if (!std::getline(in, line)) return false;
  std::stringstream hs(line);
  while (std::getline(hs, cell, ',')) out->header.push_back(cell);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream ss(line);
    while (std::getline(ss, cell, ',')) row.push_back(std::stod(cell));
    out->rows.push_back(row);
  }
  return true;
}

std::string safe(std::string s) {
  for (char& c : s)
    if (!isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

class BulletExample : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST(BulletBackend, Registered) {
  const Backend* b = find_backend("bullet");
  ASSERT_NE(b, nullptr);
  EXPECT_STREQ(b->name(), "bullet");
  EXPECT_NE(find_backend("mujoco"), nullptr) << "existing targets stay registered";
}

TEST_P(BulletExample, EmitsBuildsAndSelfChecks) {
  Programs& P = Programs::get();
  ASSERT_EQ(P.setup_error, "");
  const std::string name = fs::path(GetParam()).stem().string();
  ASSERT_TRUE(P.by_name.count(name));
  const Built& b = P.require(name);
  ASSERT_TRUE(b.emitted);
  for (const char* f : {"CMakeLists.txt", "README.md", "efc_runtime/efc_runtime.h", "efc_runtime/efc_runtime.cc",
                        "efc_runtime/efc_profile.h", "efc_runtime/efc_profile.cc"})
    EXPECT_TRUE(fs::exists(fs::path(b.dir) / f)) << f;
  EXPECT_NE(read_text(fs::path(b.dir) / "CMakeLists.txt").find("bullet-float64"), std::string::npos);
  // Effects Bullet does not simulate are named in a W0900 warning, never dropped silently.
  Diagnostics diags;
  auto obj = load_spec(b.spec, {}, diags);
  ASSERT_TRUE(obj);
  for (const Function& f : obj->functions) {
    if (f.effect.type == EffectType::Geometry) continue;
    bool named = false;
    for (const std::string& w : b.warnings)
      named |= w.rfind("W0900", 0) == 0 && w.find("'" + f.name + "'") != std::string::npos &&
               w.find(to_string(f.effect.type)) != std::string::npos;
    EXPECT_TRUE(named) << "no W0900 names function '" << f.name << "'";
  }
  ASSERT_TRUE(b.built) << b.compile_log;
  EXPECT_EQ(sh(b.exe + " --self-check 2>/dev/null"), 0) << "link frames or joint directions are wrong";
  EXPECT_EQ(sh(b.exe + " --profile nosuch --duration 1 2>/dev/null"), 2);
  EXPECT_EQ(sh(b.exe + " --profile ramp 2>/dev/null"), 2);
}

TEST_P(BulletExample, CsvPassesTheHarnessChecksUnderEveryProfile) {
  Programs& P = Programs::get();
  const std::string name = fs::path(GetParam()).stem().string();
  ASSERT_TRUE(P.by_name.count(name) && P.require(name).built);
  const Built& b = P.by_name[name];
  Diagnostics diags;
  auto obj = load_spec(b.spec, {}, diags);
  ASSERT_TRUE(obj);
  // Columns: the harness's, in the MuJoCo target's evaluation order.
  std::vector<std::string> want_header{"t"};
  for (const auto& row : build_bindings(*obj))
    for (const char* s : {".s_R", ".s_E", ".measured"}) want_header.push_back(std::string(row.name) + s);
  const std::vector<int> driven = efc::lowering::profile_driven_receptors(*obj);

  for (const char* prof : kProfiles) {
    SCOPED_TRACE(prof);
    const std::string csv = b.dir + "/" + safe(prof) + ".csv";
    const std::string csv9 = b.dir + "/" + safe(prof) + "_9.csv";
    ASSERT_EQ(sh(b.exe + " --profile " + prof + " --duration 4 --precision 17 --quiet --csv " + csv +
                 " 2>" + b.dir + "/run.err"), 0)
        << read_text(b.dir + "/run.err");
    EXPECT_NE(read_text(b.dir + "/run.err").find("steps/s"), std::string::npos);
    Csv log;
    ASSERT_TRUE(read_csv(csv, &log));
    EXPECT_EQ(log.header, want_header);
    ASSERT_EQ(log.rows.size(), 2001u);
    for (size_t k = 0; k < log.rows.size(); ++k) {
      ASSERT_EQ(log.rows[k].size(), want_header.size());
      ASSERT_EQ(log.rows[k][0], k * kDt) << "row " << k;
    }
    // The default CSV is the harness's format: %.9g.
    if (std::string(prof) == "ramp") {
      ASSERT_EQ(sh(b.exe + " --profile ramp --duration 4 --quiet --csv " + csv9), 0);
      Csv c9;
      ASSERT_TRUE(read_csv(csv9, &c9));
      ASSERT_EQ(c9.rows.size(), 2001u);
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.9g", log.rows[1234][2]);
      std::string line;
      std::ifstream in(csv9);
      for (int i = 0; i <= 1235; ++i) std::getline(in, line);
      EXPECT_NE(line.find(buf), std::string::npos) << line;
    }
    Profile profile;
    std::string error;
    int line;
    bool io;
    ASSERT_TRUE(parse_profile(prof, &profile, &error, &line, &io));
    for (const Function& f : obj->functions) {
      SCOPED_TRACE(f.name);
      const size_t col = std::find(log.header.begin(), log.header.end(), f.name + ".s_R") - log.header.begin();
      ASSERT_LT(col, log.header.size());
      std::vector<double> s_r, s_e, measured;
      for (const auto& row : log.rows) {
        s_r.push_back(row[col]);
        s_e.push_back(row[col + 1]);
        measured.push_back(row[col + 2]);
      }
      // A profile-driven receptor is where the profile says (kinematic drive).
      if (std::find(driven.begin(), driven.end(), f.receptor_index) != driven.end()) {
        const Joint& j = *obj->parts[f.receptor_index].joint;
        double lo, hi;
        receptor_range(*obj, f, &lo, &hi);
        const double q0 = j.initial.value_or(0.0);
        for (size_t k = 0; k < s_r.size(); ++k) {
          double want = profile_target(profile, f.receptor, lo, hi, q0, k * kDt, kDuration);
          if (j.type != JointType::Continuous) want = std::clamp(want, lo, hi);
          ASSERT_NEAR(s_r[k], want, 1e-12 * (1 + std::fabs(want))) << "row " << k;
        }
      }
      const std::vector<double> want = efc_test::spec_formula(*obj, f, s_r);
      for (size_t i = 0; i < want.size(); ++i)
        ASSERT_NEAR(s_e[i], want[i], 1e-9 * (1 + std::fabs(want[i]))) << "row " << i;
      const double span = std::fabs(f.effect.hi - f.effect.lo);
      const size_t last = s_e.size() - 1;
      size_t since = last;
      while (since > 0 && s_e[since - 1] == s_e[last]) --since;
      const bool held = (last - since) * kDt >= 1.0;
      switch (f.effect.type) {
        case EffectType::Geometry:
          // Within 2% once held, for the compiler's default gains; a stiffness
          // the spec gives may be too soft for that (the MuJoCo target warns,
          // and MuJoCo sags the same): parity compares those with MuJoCo.
          if (held && !f.effect.stiffness) {
            EXPECT_NEAR(measured[last], s_e[last], 0.02 * span);
          }
          break;
        case EffectType::Illumination:
        case EffectType::Airflow:
          for (size_t i = 0; i < want.size(); ++i) ASSERT_NEAR(measured[i], s_e[i], 1e-9 * (1 + span));
          break;
        case EffectType::Temperature: {
          // First-order lag from ambient; every logged step (t = 0 included)
          // has advanced it by dt towards that step's s_E (the runtime's order).
          double t_ref = f.effect.lo;
          for (size_t i = 0; i < want.size(); ++i) {
            t_ref += (s_e[i] - t_ref) * (1 - std::exp(-kDt / *f.effect.time_constant));
            ASSERT_NEAR(measured[i], t_ref, 1e-6 * (1 + span)) << "row " << i;
          }
          break;
        }
        case EffectType::Fluid:
          if (held) {
            const double r = *f.effect.droplet_radius;
            const double resolution = 4.0 / 3.0 * M_PI * r * r * r * 1000.0 / 0.5 * 60.0;
            // Counted over the 0.5 s window, which may hold one step more
            // (its edge falls between steps): one droplet plus one step's flow.
            EXPECT_NEAR(measured[last], s_e[last], resolution + std::fabs(s_e[last]) * kDt / 0.5 + 1e-9);
          }
          break;
      }
    }
  }
}

TEST_P(BulletExample, ParityHoldsUnderEveryProfile) {
  Programs& P = Programs::get();
  const std::string name = fs::path(GetParam()).stem().string();
  ASSERT_TRUE(P.by_name.count(name) && P.require(name).built);
  ASSERT_TRUE(fs::exists(kEfc)) << "build the efc target first";
  const Built& b = P.by_name[name];
  for (const char* prof : kProfiles) {
    SCOPED_TRACE(prof);
    const std::string out = b.dir + "/parity.out";
    const int rc = sh(kEfc + " parity " + b.spec + " --profile " + prof + " --duration 4 --bullet-exe " +
                      b.exe + " >" + out + " 2>&1");
    const std::string text = read_text(out);
    EXPECT_EQ(rc, 0) << text;
    EXPECT_NE(text.find("parity: holds"), std::string::npos) << text;
  }
}

INSTANTIATE_TEST_SUITE_P(AllExamples, BulletExample, ::testing::ValuesIn(example_files()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return safe(fs::path(info.param).stem().string());
                         });

// `efc parity` on its own: builds the program with cmake into the cache,
// reuses it on the second run, and fails (exit 1) when the two disagree.
TEST(BulletParity, BuildsWithCmakeIntoTheCacheAndReusesIt) {
  ASSERT_TRUE(fs::exists(kEfc)) << "build the efc target first";
  const fs::path tmp = fs::temp_directory_path() / ("efc-parity-test-" + std::to_string(getpid()));
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  const std::string spec = std::string(EFC_SOURCE_DIR) + "/examples/pedal_bin.json";
  const std::string env = "TMPDIR=" + tmp.string() + " ";
  const std::string cmd = env + kEfc + " parity " + spec + " --profile press:2 --duration 2 --csv-dir " +
                          (tmp / "csv").string();
  ASSERT_EQ(sh(cmd + " >" + (tmp / "a.out").string() + " 2>&1"), 0) << read_text(tmp / "a.out");
  const std::string first = read_text(tmp / "a.out");
  EXPECT_NE(first.find("parity: building"), std::string::npos) << first;
  EXPECT_NE(first.find("open_lid"), std::string::npos);
  EXPECT_TRUE(fs::exists(tmp / "csv" / "bullet.csv"));
  EXPECT_TRUE(fs::exists(tmp / "csv" / "mujoco.csv"));
  ASSERT_EQ(sh(cmd + " >" + (tmp / "b.out").string() + " 2>&1"), 0);
  EXPECT_NE(read_text(tmp / "b.out").find("parity: reusing"), std::string::npos) << read_text(tmp / "b.out");
  // A program whose s_E disagrees: parity exits 1. (A shell script that
  // writes the harness's CSV with one s_E value changed.)
  const fs::path fake = tmp / "fake.sh";
  {
    std::ofstream out(fake);
    out << "#!/bin/sh\nwhile [ $# -gt 0 ]; do [ \"$1\" = --csv ] && out=$2; shift; done\n"
        << "awk -F, 'BEGIN{OFS=\",\"} NR==500{$3=$3+1} {print}' " << (tmp / "csv" / "mujoco.csv").string()
        << " > \"$out\"\n";
  }
  fs::permissions(fake, fs::perms::owner_all);
  const int rc = sh(kEfc + " parity " + spec + " --profile press:2 --duration 2 --bullet-exe " + fake.string() +
                    " >" + (tmp / "c.out").string() + " 2>&1");
  EXPECT_EQ(rc, 1) << read_text(tmp / "c.out");
  EXPECT_EQ(sh(kEfc + " parity " + spec + " --profile press:2 --duration -1 >/dev/null 2>&1"), 2);
  fs::remove_all(tmp);
}
