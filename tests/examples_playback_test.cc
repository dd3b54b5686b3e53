// Every example: checks, compiles for MuJoCo, loads in the real MuJoCo with no
// warning, and plays back under ramp, press and hold profiles; the logged s_E
// matches the spec's formula (recomputed here from the logged s_R, written
// from the spec's text rather than with the runtime), and `measured` shows the
// effect was realised in the simulation.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "compiler/core/load.h"
#include "compiler/core/resolve.h"
#include "harness/mujoco_errors.h"
#include "harness/play.h"
#include "spec_formula.h"

namespace fs = std::filesystem;
using namespace efc;

namespace {

std::vector<std::string> example_files() {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(fs::path(EFC_SOURCE_DIR) / "examples"))
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

using efc_test::spec_formula;

struct Case {
  std::string file;
  std::string profile;
};

class ExamplePlayback : public ::testing::TestWithParam<Case> {};

}  // namespace

TEST(Examples, CoverEveryMappingEffectPair) {
  std::set<std::pair<MappingType, EffectType>> seen;
  bool chain = false, mesh = false;
  for (const std::string& file : example_files()) {
    Diagnostics diags;
    auto obj = load_spec(file, {}, diags);
    ASSERT_TRUE(obj) << file;
    std::set<int> geometry_effectors;
    for (const Function& f : obj->functions) {
      seen.insert({f.mapping.type, f.effect.type});
      if (f.effect.type == EffectType::Geometry) geometry_effectors.insert(f.effector_index);
    }
    for (const Function& f : obj->functions) chain |= geometry_effectors.count(f.receptor_index) > 0;
    for (const Part& p : obj->parts) mesh |= p.geometry.kind == GeomKind::Mesh;
  }
  EXPECT_EQ(seen.size(), 20u) << "every mapping x effect pair needs an example";
  EXPECT_TRUE(chain) << "an example must chain two functions";
  EXPECT_TRUE(mesh) << "an example must use meshes";
}

TEST(Examples, CheckCleanAndLoadInMujocoWithoutWarning) {
  install_mujoco_handlers();
  const Backend* mujoco = find_backend("mujoco");
  ASSERT_NE(mujoco, nullptr);
  for (const std::string& file : example_files()) {
    SCOPED_TRACE(file);
    Diagnostics diags;
    auto obj = load_spec(file, {}, diags);
    ASSERT_TRUE(obj);
    EXPECT_EQ(diags.items().size(), 0u) << "examples should compile without diagnostics";
    const fs::path dir = fs::temp_directory_path() / ("efc-ex-" + obj->name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    ASSERT_TRUE(mujoco->emit(*obj, dir.string(), diags));
    take_mujoco_warnings();
    char error[1024] = "";
    mjModel* m = mj_loadXML((dir / (obj->name + ".xml")).c_str(), nullptr, error, sizeof error);
    ASSERT_NE(m, nullptr) << error;
    for (const Part& p : obj->parts) {
      EXPECT_GE(mj_name2id(m, mjOBJ_BODY, p.name.c_str()), 0) << p.name;
      if (p.joint && p.joint->movable()) {
        EXPECT_GE(mj_name2id(m, mjOBJ_JOINT, p.name.c_str()), 0) << p.name;
      }
    }
    mjData* d = mj_makeData(m);
    for (int i = 0; i < 200; ++i) mj_step(m, d);
    EXPECT_TRUE(take_mujoco_warnings().empty());
    mj_deleteData(d);
    mj_deleteModel(m);
    fs::remove_all(dir);
  }
}

TEST_P(ExamplePlayback, SEMatchesSpecAndEffectIsRealised) {
  const Case& c = GetParam();
  Diagnostics diags;
  auto obj = load_spec(c.file, {}, diags);
  ASSERT_TRUE(obj);
  PlayOptions opts;
  std::string error;
  int line;
  bool io;
  ASSERT_TRUE(parse_profile(c.profile, &opts.profile, &error, &line, &io)) << error;
  opts.duration = 4.0;
  opts.dt = 0.002;
  PlayLog log;
  ASSERT_EQ(play(*obj, opts, diags, &log), 0);
  for (const auto& d : diags.items()) ADD_FAILURE() << format_text(d);
  ASSERT_EQ(log.rows.front()[0], 0.0);
  ASSERT_EQ(log.rows.size(), 2001u);

  for (const Function& f : obj->functions) {
    SCOPED_TRACE(f.name);
    const auto col = std::find(log.columns.begin(), log.columns.end(), f.name + ".s_R") - log.columns.begin();
    ASSERT_LT(static_cast<size_t>(col), log.columns.size());
    std::vector<double> s_r, s_e, measured;
    for (const auto& row : log.rows) {
      s_r.push_back(row[col]);
      s_e.push_back(row[col + 1]);
      measured.push_back(row[col + 2]);
    }
    const std::vector<double> want = spec_formula(*obj, f, s_r);
    for (size_t i = 0; i < want.size(); ++i)
      ASSERT_NEAR(s_e[i], want[i], 1e-9 * (1 + std::fabs(want[i]))) << "row " << i;

    // The effect, as the simulation realised it.
    const double e_lo = f.effect.lo, e_hi = f.effect.hi, span = std::fabs(e_hi - e_lo);
    const size_t last = log.rows.size() - 1;
    switch (f.effect.type) {
      case EffectType::Geometry: {
        // Steady state: once s_E has held for 1 s, the joint is within 2% of the range.
        size_t since = last;
        while (since > 0 && s_e[since - 1] == s_e[last]) --since;
        if ((last - since) * opts.dt >= 1.0) {
          EXPECT_NEAR(measured[last], s_e[last], 0.02 * span);
        }
        break;
      }
      case EffectType::Illumination:
      case EffectType::Airflow:
        for (size_t i = 0; i < want.size(); ++i) ASSERT_NEAR(measured[i], s_e[i], 1e-4 * (1 + span));
        break;
      case EffectType::Temperature: {
        // First-order lag: T stays between ambient and the hottest target, and moves toward s_E.
        const double tau = *f.effect.time_constant;
        double t_ref = e_lo;
        for (size_t i = 0; i < want.size(); ++i) {
          // Each step maps s_R to s_E, then advances the lag by dt towards it.
          t_ref += (s_e[i] - t_ref) * (1 - std::exp(-opts.dt / tau));
          ASSERT_NEAR(measured[i], t_ref, 1e-6 * (1 + span)) << "row " << i;
        }
        break;
      }
      case EffectType::Fluid: {
        // Flow from counted droplets over the last window follows s_E once it has held.
        size_t since = last;
        while (since > 0 && s_e[since - 1] == s_e[last]) --since;
        if ((last - since) * opts.dt >= 1.0) {
          const double r = *f.effect.droplet_radius;
          const double drop_l = 4.0 / 3.0 * M_PI * r * r * r * 1000.0;
          // The window holds a whole number of droplets and may catch one at each
          // edge: two droplets' worth of flow, in L/min.
          const double resolution = 2 * drop_l / 0.5 * 60.0;
          EXPECT_NEAR(measured[last], s_e[last], resolution + 1e-9);
        }
        break;
      }
    }
  }
}

namespace {
std::vector<Case> all_cases() {
  std::vector<Case> out;
  for (const std::string& f : example_files())
    for (const char* p : {"ramp", "sweep", "press:3", "hold:hi", "hold:lo"}) out.push_back({f, p});
  return out;
}
std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  std::string n = fs::path(info.param.file).stem().string() + "_" + info.param.profile;
  for (char& ch : n)
    if (!isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
}
}  // namespace

INSTANTIATE_TEST_SUITE_P(AllExamples, ExamplePlayback, ::testing::ValuesIn(all_cases()), case_name);
