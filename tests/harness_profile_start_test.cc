// efc play starts every profile-driven receptor where its profile starts
// (shared/spec/cli.md): ramp, sweep and press:N at the lower limit, hold:V at
// the initial position, csv:FILE at its first row. Found when the harness was
// tried against its contract: the first row showed the spec's initial
// position, so a binary function whose threshold equals it switched twice on
// one ramp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "compiler/core/load.h"
#include "harness/play.h"
#include "tests/process_temp_dir.h"

namespace fs = std::filesystem;
using namespace efc;

namespace {

// A lever on [0, 1] rad that starts at 0.5, switching a lamp at exactly 0.5.
constexpr const char* kSpec = R"({"efc": 1, "name": "threshold_at_initial",
 "parts": [
  {"name": "base", "role": "base", "geometry": {"box": {"size": [0.1, 0.1, 0.02]}}},
  {"name": "lever", "role": "receptor",
   "geometry": {"box": {"size": [0.02, 0.02, 0.05], "center": [0, 0, 0.05]}},
   "joint": {"type": "revolute", "parent": "base", "axis": [0, 1, 0], "origin": [0, 0, 0.03],
             "range": [0, 1], "initial": 0.5}},
  {"name": "lamp", "role": "effector", "geometry": {"sphere": {"radius": 0.02, "center": [0, 0, 0.2]}},
   "joint": {"type": "fixed", "parent": "base"}}],
 "functions": [
  {"name": "light", "receptor": "lever", "effector": "lamp",
   "mapping": {"type": "binary", "threshold": 0.5}, "effect": {"type": "illumination", "range": [0, 100]}}]})";

Object load() {
  static const efc_test::ProcessTempDir root("efc-profile-start-");
  const fs::path& dir = root.path();
  fs::create_directories(dir);
  const fs::path spec = dir / "spec.json";
  std::ofstream(spec) << kSpec;
  Diagnostics diags;
  auto obj = load_spec(spec.string(), {}, diags);
  EXPECT_TRUE(obj.has_value());
  return std::move(*obj);
}

PlayLog play_with(const Object& obj, const std::string& profile_text) {
  PlayOptions opts;
  std::string error;
  int line = 0;
  bool io = false;
  EXPECT_TRUE(parse_profile(profile_text, &opts.profile, &error, &line, &io)) << error;
  opts.duration = 2;
  Diagnostics diags;
  PlayLog log;
  EXPECT_EQ(play(obj, opts, diags, &log), 0);
  return log;
}

int switches(const PlayLog& log) {
  int n = 0;
  for (size_t r = 1; r < log.rows.size(); ++r) n += log.rows[r][2] != log.rows[r - 1][2];
  return n;
}

}  // namespace

TEST(ProfileStart, RampSweepAndPressStartAtTheLowerLimit) {
  const Object obj = load();
  for (const char* profile : {"ramp", "sweep", "press:2"}) {
    SCOPED_TRACE(profile);
    const PlayLog log = play_with(obj, profile);
    ASSERT_GT(log.rows.size(), 2u);
    EXPECT_EQ(log.rows[0][0], 0.0);
    EXPECT_EQ(log.rows[0][1], 0.0) << "s_R at t = 0 is the lower limit";
    EXPECT_EQ(log.rows[0][2], 0.0) << "the lamp is off below the threshold";
  }
}

TEST(ProfileStart, ABinaryThresholdAtTheInitialPositionSwitchesOncePerCrossing) {
  const Object obj = load();
  EXPECT_EQ(switches(play_with(obj, "ramp")), 1);
  EXPECT_EQ(switches(play_with(obj, "sweep")), 2);
  EXPECT_EQ(switches(play_with(obj, "press:2")), 4);
}

TEST(ProfileStart, HoldStartsAtTheInitialPosition) {
  const Object obj = load();
  const PlayLog log = play_with(obj, "hold:lo");
  EXPECT_EQ(log.rows[0][1], 0.5);
  EXPECT_EQ(log.rows[0][2], 100.0);
  EXPECT_NEAR(log.rows.back()[1], 0.0, 0.01);
}
