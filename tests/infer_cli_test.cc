// `efc infer` as a user meets it: a synthetic recording in, a spec out that
// passes efc check, compiles to every target and plays; the joint it finds
// against the truth (efc eval); and bad sequences (no depth, no poses, a
// missing frame, NaN in a pose, a part whose masks are empty, no masks at
// all) giving located errors or warnings, never a crash and never a partial
// output.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sequence/sequence.h"
#include "tests/efc_cli.h"
#include "tests/truth_csv.h"

namespace {

namespace fs = std::filesystem;
using efc_test::read_file;
using efc_test::run_efc;
using json = nlohmann::json;
namespace seq = efc::seq;

fs::path fresh_dir(const std::string& stem) {
  fs::path p = fs::temp_directory_path() / ("efc-infer-" + std::to_string(getpid()) + "-" + stem);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

// A copy of a committed synthetic sequence (tests/data/synth-suite) to break.
fs::path committed_copy(const fs::path& dir, const std::string& name) {
  const fs::path src = fs::path(EFC_SOURCE_DIR) / "tests/data/synth-suite/s0000_binary-illumination_revolute/seq";
  const fs::path dst = dir / name;
  fs::copy(src, dst, fs::copy_options::recursive);
  return dst;
}

TEST(InferCli, SyntheticDrawerToSpecThatCompilesAndPlays) {
  const fs::path dir = fresh_dir("e2e");
  const std::string seq = (dir / "seq").string(), out = (dir / "out").string();
  auto r = run_efc("synth " + std::string(EFC_SOURCE_DIR) + "/examples/kitchen_drawer.json -o " + seq +
                   " --frames 90 --width 320 --height 240 --noise mild --seed 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_efc("infer " + seq + " -o " + out + " --report");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("drawer"), std::string::npos) << r.out;  // the --report summary
  const json spec = json::parse(read_file(dir / "out/spec.json"));
  ASSERT_TRUE(spec.contains("x-efc-object-to-world"));
  EXPECT_EQ(spec["x-efc-object-to-world"].size(), 16u);
  bool drawer = false;
  for (const json& p : spec["parts"]) {
    if (p["name"] == "led_strip") {
      // Inside the cabinet, never seen (E1058): its function is kept, a
      // sphere stands in for it (E1066).
      EXPECT_TRUE(p["geometry"].contains("sphere")) << p;
      EXPECT_EQ(p["joint"]["type"], "fixed") << p;
      continue;
    }
    EXPECT_TRUE(fs::exists(dir / "out" / p["geometry"]["mesh"].get<std::string>())) << p;
    if (p["name"] == "drawer") {
      drawer = true;
      EXPECT_EQ(p["joint"]["type"], "prismatic") << p;
    }
  }
  EXPECT_TRUE(drawer);
  EXPECT_NE(r.err.find("E1066"), std::string::npos) << r.err;
  ASSERT_EQ(spec["functions"].size(), 1u);
  EXPECT_EQ(spec["functions"][0]["effector"], "led_strip");
  const json report = json::parse(read_file(dir / "out/report.json"));
  std::vector<std::string> stage_names;
  for (const json& s : report["stages"]) {
    stage_names.push_back(s["name"].get<std::string>());
    EXPECT_GE(s["seconds"].get<double>(), 0.0) << s;
  }
  EXPECT_EQ(stage_names, (std::vector<std::string>{"observations", "ego_motion", "part_motion", "grip_motion",
                                                   "articulation", "reconstruction", "axis_prior", "templates"}));
  // The drawer's position per frame (parts[].joint.q) follows the truth's
  // (truth/joints.csv, one row per frame), both from where it was first seen.
  {
    const std::vector<double> truth_q = efc::test::read_joints_csv((dir / "seq/truth/joints.csv").string())["drawer"];
    ASSERT_FALSE(truth_q.empty());
    bool found = false;
    for (const json& p : report["parts"]) {
      if (p["name"] != "drawer") continue;
      found = true;
      // The estimated axis may point the other way: the better sign.
      // Returns {median, worst} error from the first frame with a value.
      auto errors_of = [&](const json& q) {
        std::pair<double, double> best{1e9, 1e9};
        int first = -1;
        for (int f = 0; f < 90; ++f)
          if (!q[f].is_null() && first < 0) first = f;
        if (first < 0) return best;
        for (double sign : {1.0, -1.0}) {
          std::vector<double> errors;
          for (int f = first; f < 90; ++f)
            if (!q[f].is_null())
              errors.push_back(std::abs(sign * (q[f].get<double>() - q[first].get<double>()) - (truth_q[f] - truth_q[first])));
          std::sort(errors.begin(), errors.end());
          if (errors[errors.size() / 2] < best.first) best = {errors[errors.size() / 2], errors.back()};
        }
        return best;
      };
      ASSERT_TRUE(p["joint"].contains("q")) << p["joint"];
      ASSERT_EQ(p["joint"]["q"].size(), 90u);
      ASSERT_GE(truth_q.size(), 90u);
      // The frames where the drawer is pulled furthest out show little of
      // it (measured: up to 6 cm short there), so the median is held tight
      // and the worst frame loosely.
      const auto [median, worst] = errors_of(p["joint"]["q"]);
      EXPECT_LT(median, 0.005) << "the drawer's estimated position is off by " << median << " m in the median";
      EXPECT_LT(worst, 0.1) << "the drawer's estimated position is off by up to " << worst << " m";
      // The part's track gave q; the hand's contacts give it too (q_hand,
      // the templates' second candidate for s_R): noisier (measured: 1.5
      // cm median, 4.5 cm worst), from the first contact on.
      EXPECT_EQ(p["joint"]["source"], "part");
      ASSERT_TRUE(p["joint"].contains("q_hand")) << p["joint"];
      ASSERT_EQ(p["joint"]["q_hand"].size(), 90u);
      const auto [median_hand, worst_hand] = errors_of(p["joint"]["q_hand"]);
      EXPECT_LT(median_hand, 0.03) << "the hand's drawer position is off by " << median_hand << " m in the median";
      EXPECT_LT(worst_hand, 0.1) << "the hand's drawer position is off by up to " << worst_hand << " m";
      // A drawer slides beside no axis through itself: its own track types
      // it prismatic, never a slide found under a slipping turn. The
      // track's scores still show the hinge and the hinge that also slides
      // (the figures that rule decides on), as numbers.
      EXPECT_FALSE(p["joint"].contains("slide_over_turn")) << p["joint"];
      EXPECT_FALSE(p["joint"].contains("turn_taken_for_slip")) << p["joint"];
      EXPECT_EQ(p["joint"]["from_part"]["type"], "prismatic") << p["joint"]["from_part"];
      const json& part_bic = p["joint"]["from_part"]["bic"];
      ASSERT_TRUE(part_bic.contains("revolute_and_slide")) << p["joint"]["from_part"];
      EXPECT_TRUE(part_bic["revolute_and_slide"].is_number() && part_bic["revolute"].is_number()) << part_bic;
    }
    EXPECT_TRUE(found);
  }

  // The spec compiles unchanged to every target and plays.
  r = run_efc("check " + out + "/spec.json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_efc("compile " + out + "/spec.json --target all -o " + (dir / "compiled").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  for (const char* t : {"mujoco", "urdf", "bullet", "genesis", "isaaclab", "omnigibson"})
    EXPECT_TRUE(fs::exists(dir / "compiled" / t)) << t;
  r = run_efc("play " + out + "/spec.json --profile sweep --duration 1 --csv " + (dir / "play.csv").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "play.csv"));

  // The drawer's axis against the truth, in the world frame: 2 to 3.2
  // degrees off in yaw (measured: 0.036 to 0.046 rad with the world
  // anchored a millimetre or three apart, 0.056 as anchored now; the
  // anchor itself is 0.06 degrees off the truth here), so within 4 degrees.
  r = run_efc("eval --pred " + out + "/spec.json --gt " + seq + "/truth/spec.json --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json ev = json::parse(r.out);
  bool scored = false;
  for (const json& j : ev["joints"]) {
    if (j["part"] != "drawer") continue;
    scored = true;
    EXPECT_TRUE(j["type_correct"].get<bool>()) << j;
    EXPECT_LT(j["axis_error_rad"].get<double>(), 0.07) << j;
  }
  EXPECT_TRUE(scored) << r.out;

  // A part no function names ('object') may move all the same: the drawer,
  // relabelled so and its functions taken away, is still prismatic.
  json meta = json::parse(read_file(dir / "seq/meta.json"));
  ASSERT_TRUE(meta["parts"].contains("drawer"));
  meta["parts"]["drawer"] = "object";
  meta.erase("functions");
  std::ofstream(dir / "seq/meta.json") << meta.dump(2);
  r = run_efc("infer " + seq + " -o " + (dir / "out-object").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  bool moved = false;
  const json relabelled = json::parse(read_file(dir / "out-object/spec.json"));
  for (const json& p : relabelled["parts"])
    if (p["name"] == "drawer") moved = p.contains("joint") && p["joint"]["type"] == "prismatic";
  EXPECT_TRUE(moved) << read_file(dir / "out-object/spec.json");
  fs::remove_all(dir);
}

TEST(InferCli, ParkedPartsAreFixedAndTheSpecChecks) {
  // The committed kettle: base and jug never move (one is the root, the
  // other hangs from it by a fixed joint).
  const fs::path dir = fresh_dir("kettle");
  const fs::path seq = committed_copy(dir, "seq");
  auto r = run_efc("infer " + seq.string() + " -o " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json spec = json::parse(read_file(dir / "out/spec.json"));
  int roots = 0;
  for (const json& p : spec["parts"]) {
    if (!p.contains("joint")) {
      ++roots;
    } else if (p["name"] == "base" || p["name"] == "jug") {
      EXPECT_EQ(p["joint"]["type"], "fixed") << p;
    }
  }
  EXPECT_EQ(roots, 1);
  EXPECT_EQ(run_efc("check " + (dir / "out/spec.json").string()).exit_code, 0);
  fs::remove_all(dir);
}

TEST(InferCli, MissingInputsAreNamedAndNothingIsWritten) {
  const fs::path dir = fresh_dir("missing");
  {
    const fs::path seq = committed_copy(dir, "nodepth");
    fs::remove_all(seq / "depth");
    auto r = run_efc("infer " + seq.string() + " -o " + (dir / "o1").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("error[E1050]"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("depth/"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "o1"));
  }
  {
    const fs::path seq = committed_copy(dir, "noposes");
    fs::remove(seq / "poses.txt");
    auto r = run_efc("infer " + seq.string() + " -o " + (dir / "o2").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("error[E1051]"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "o2"));
  }
  {
    const fs::path seq = committed_copy(dir, "noframe");
    fs::remove(seq / "depth/000017.png");
    auto r = run_efc("infer " + seq.string() + " -o " + (dir / "o3").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("depth/000017.png"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "o3"));
  }
  {
    const fs::path seq = committed_copy(dir, "nanpose");
    std::string poses = read_file(seq / "poses.txt");
    const size_t line = poses.find('\n', poses.find('\n') + 1);  // after the header and frame 0
    poses.insert(line + 1, "0.0001 nan 0 0 0 0 0 1\n");
    std::ofstream(seq / "poses.txt") << poses;
    auto r = run_efc("infer " + seq.string() + " -o " + (dir / "o4").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("poses.txt:3:"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "o4"));
  }
  {
    // A folder that is not an earlier infer output is never replaced.
    const fs::path seq = committed_copy(dir, "ok");
    fs::create_directories(dir / "mine");
    std::ofstream(dir / "mine/notes.txt") << "keep me\n";
    auto r = run_efc("infer " + seq.string() + " -o " + (dir / "mine").string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(fs::exists(dir / "mine/notes.txt"));
  }
  EXPECT_EQ(run_efc("infer " + (dir / "absent").string() + " -o " + (dir / "o5").string()).exit_code, 1);
  EXPECT_EQ(run_efc("infer " + (dir / "absent").string() + " -o x --threads 0").exit_code, 2);
  fs::remove_all(dir);
}

TEST(InferCli, EmptyMasksAndNoMasksAreWarningsNotCrashes) {
  const fs::path dir = fresh_dir("masks");
  {
    // The LED's masks are all empty: it is left out with a warning.
    const fs::path seq = committed_copy(dir, "emptyled");
    seq::Image8 empty;
    empty.width = 160, empty.height = 120, empty.channels = 1;
    empty.pixels.assign(160 * 120, 0);
    std::string error;
    for (const auto& e : fs::directory_iterator(seq / "masks/led"))
      ASSERT_TRUE(seq::write_png_gray8(e.path().string(), empty, &error)) << error;
    auto r = run_efc("infer " + seq.string() + " -o " + (dir / "o1").string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("warning[E1058]"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("'led'"), std::string::npos) << r.err;
    EXPECT_EQ(run_efc("check " + (dir / "o1/spec.json").string()).exit_code, 0);
  }
  {
    // No masks at all: the motion fallback, with its warning.
    const fs::path seq = committed_copy(dir, "nomasks");
    fs::remove_all(seq / "masks");
    auto r = run_efc("infer " + seq.string() + " -o " + (dir / "o2").string());
    EXPECT_NE(r.err.find("warning[E1053]"), std::string::npos) << r.err;
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err;
    if (r.exit_code == 0) EXPECT_EQ(run_efc("check " + (dir / "o2/spec.json").string()).exit_code, 0);
    else EXPECT_FALSE(fs::exists(dir / "o2"));
  }
  fs::remove_all(dir);
}

}  // namespace
