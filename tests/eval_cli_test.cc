// `efc eval` as a user meets it: the metrics of real examples against
// themselves, a rotated axis, a moved frame, a missing prediction, a list of
// pairs, masks, JSON output and located errors.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "sequence/sequence.h"
#include "tests/efc_cli.h"

namespace {

namespace fs = std::filesystem;
using efc_test::read_file;
using efc_test::run_efc;
using nlohmann::json;

const std::string kExamples = std::string(EFC_SOURCE_DIR) + "/examples/";
const std::string kLamp = kExamples + "desk_lamp.json";
const std::string kFaucet = kExamples + "kitchen_faucet.json";  // has meshes

// A fresh temporary folder, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    root_ = fs::temp_directory_path() / ("efc-eval-cli-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  ~TempDir() { fs::remove_all(root_); }
  std::string path(const std::string& name) const { return (root_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }

 private:
  fs::path root_;
};

json lamp_json() { return json::parse(read_file(kLamp)); }

// The lamp with its head's hinge (axis +y) turned by `angle` about x.
std::string rotated_lamp(const TempDir& dir, double angle) {
  json spec = lamp_json();
  for (json& part : spec["parts"])
    if (part["name"] == "head") part["joint"]["axis"] = {0, std::cos(angle), std::sin(angle)};
  return dir.write("rotated.json", spec.dump());
}

json eval_json(const std::string& args) {
  const auto r = run_efc("eval " + args + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return json::parse(r.out);
}

const json& joint(const json& result, const std::string& part) {
  for (const json& j : result["joints"])
    if (j["part"] == part) return j;
  ADD_FAILURE() << "no joint " << part;
  return result;
}

TEST(EvalCli, AnExampleAgainstItselfScoresPerfectly) {
  for (const std::string& spec : {kLamp, kFaucet}) {
    const json r = eval_json("--pred " + spec + " --gt " + spec);
    ASSERT_FALSE(r["joints"].empty()) << spec;
    for (const json& j : r["joints"]) {
      EXPECT_TRUE(j["type_correct"].get<bool>());
      EXPECT_EQ(j["axis_error_rad"].get<double>(), 0);
      EXPECT_EQ(j["origin_error_m"].get<double>(), 0);
    }
    for (const json& f : r["functions"]) EXPECT_TRUE(f["correct"].get<bool>());
    for (const json& c : r["chamfer"]) EXPECT_EQ(c["cd_m2"].get<double>(), 0) << c;
    EXPECT_EQ(r["failures"], 0);
    EXPECT_TRUE(r["masks"].is_null());
  }
  const auto text = run_efc("eval --pred " + kLamp + " --gt " + kLamp);
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("100.0"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("Mask: not given"), std::string::npos) << text.out;
}

TEST(EvalCli, ARotatedAxisScoresItsAngle) {
  TempDir dir;
  const json r = eval_json("--pred " + rotated_lamp(dir, 0.25) + " --gt " + kLamp);
  EXPECT_NEAR(joint(r, "head")["axis_error_rad"].get<double>(), 0.25, 1e-9);
  EXPECT_NEAR(joint(r, "head")["origin_error_m"].get<double>(), 0, 1e-9);  // the lines still cross
  EXPECT_TRUE(joint(r, "head")["type_correct"].get<bool>());
  EXPECT_EQ(joint(r, "switch")["axis_error_rad"].get<double>(), 0);
}

TEST(EvalCli, TheObjectToWorldExtensionIsApplied) {
  TempDir dir;
  json spec = lamp_json();
  spec["x-efc-object-to-world"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0.1, 0, 0, 0, 1};  // 10 cm up
  const json r = eval_json("--pred " + dir.write("up.json", spec.dump()) + " --gt " + kLamp);
  EXPECT_NEAR(joint(r, "head")["origin_error_m"].get<double>(), 0.1, 1e-9);  // parallel hinges 10 cm apart
  EXPECT_EQ(joint(r, "switch")["origin_error_m"].get<double>(), 0);         // prismatic truth
  for (const json& c : r["chamfer"]) EXPECT_GT(c["cd_m2"].get<double>(), 1e-4);

  spec["x-efc-object-to-world"] = {1, 2, 3};
  const std::string bad = dir.write("bad.json", spec.dump(2));
  const auto as_truth = run_efc("eval --pred " + kLamp + " --gt " + bad);
  EXPECT_EQ(as_truth.exit_code, 1);
  EXPECT_NE(as_truth.err.find(bad + ":"), std::string::npos) << as_truth.err;
  EXPECT_NE(as_truth.err.find("error[E1020]"), std::string::npos) << as_truth.err;
  const json as_pred = eval_json("--pred " + bad + " --gt " + kLamp);  // a broken prediction: scored
  EXPECT_FALSE(as_pred["prediction_loaded"].get<bool>());
  EXPECT_EQ(as_pred["failures"], 2);
}

TEST(EvalCli, ATruthSpecTakesItsPoseFromObjectPoseJsonBesideIt) {
  // A sequence's truth/: spec.json in its own frame, object_pose.json
  // placing it 10 cm up; the prediction says the same with the extension.
  TempDir dir;
  fs::create_directories(dir.path("truth"));
  const std::string gt = dir.write("truth/spec.json", lamp_json().dump());
  dir.write("truth/object_pose.json", R"({"object_to_world": [1,0,0,0, 0,1,0,0, 0,0,1,0.1, 0,0,0,1]})");
  json pred = lamp_json();
  pred["x-efc-object-to-world"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0.1, 0, 0, 0, 1};
  const json r = eval_json("--pred " + dir.write("pred.json", pred.dump()) + " --gt " + gt);
  EXPECT_NEAR(joint(r, "head")["origin_error_m"].get<double>(), 0.0, 1e-9);
  for (const json& c : r["chamfer"]) EXPECT_NEAR(c["cd_m2"].get<double>(), 0.0, 1e-12);
  // Without the pose file the truth stays where its spec puts it.
  fs::remove(dir.path("truth/object_pose.json"));
  EXPECT_NEAR(joint(eval_json("--pred " + dir.path("pred.json") + " --gt " + gt), "head")["origin_error_m"].get<double>(),
              0.1, 1e-9);
  // A malformed pose file is a located error for the truth.
  dir.write("truth/object_pose.json", R"({"object_to_world": [1, 2]})");
  const auto bad = run_efc("eval --pred " + dir.path("pred.json") + " --gt " + gt);
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("object_pose.json"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("error[E1020]"), std::string::npos) << bad.err;
}

TEST(EvalCli, AMissingPredictionScoresFailures) {
  TempDir dir;
  const auto r = run_efc("eval --json --pred " + dir.path("nothing.json") + " --gt " + kLamp);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("failed prediction"), std::string::npos) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["failures"], 2);
  for (const json& jt : j["joints"]) {
    EXPECT_FALSE(jt["type_correct"].get<bool>());
    EXPECT_NEAR(jt["axis_error_rad"].get<double>(), M_PI / 2, 1e-12);
    EXPECT_EQ(jt["origin_error_m"].get<double>(), 1.0);
  }
  for (const json& f : j["functions"]) EXPECT_FALSE(f["correct"].get<bool>());
  for (const json& c : j["chamfer"]) EXPECT_TRUE(c["cd_m2"].is_null());
}

TEST(EvalCli, JsonHasTheDocumentedKeys) {
  const json r = eval_json("--pred " + kLamp + " --gt " + kLamp);
  for (const char* key : {"joints", "functions", "chamfer", "failures"}) EXPECT_TRUE(r.contains(key)) << key;
  for (const char* key : {"part", "type_correct", "axis_error_rad", "origin_error_m"})
    EXPECT_TRUE(r["joints"][0].contains(key)) << key;
  for (const char* key : {"name", "effect_correct", "mapping_correct", "correct"})
    EXPECT_TRUE(r["functions"][0].contains(key)) << key;
  for (const char* key : {"part", "cd_m2"}) EXPECT_TRUE(r["chamfer"][0].contains(key)) << key;
}

TEST(EvalCli, AListOfThreePairsGivesThePapersTables) {
  TempDir dir;
  rotated_lamp(dir, 0.3);
  const std::string list = dir.write("pairs.txt",
                                     "# PRED GT\n" + kLamp + " " + kLamp + "\n"
                                     "rotated.json " + kLamp + "   # head turned 0.3 rad\n"
                                     "missing.json " + kLamp + "\n");
  const auto r = run_efc("eval --json --list " + list);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["pairs"].size(), 3u);
  const json& a = j["aggregate"];
  EXPECT_EQ(a["pairs"], 3);
  EXPECT_EQ(a["articulation"]["joints"], 6);
  EXPECT_NEAR(a["articulation"]["type_accuracy_pct"].get<double>(), 400.0 / 6, 1e-9);
  EXPECT_NEAR(a["articulation"]["axis_error_rad_mean"].get<double>(), (0.3 + M_PI) / 6, 1e-9);
  EXPECT_NEAR(a["articulation"]["origin_error_m_mean"].get<double>(), 2.0 / 6, 1e-9);
  EXPECT_NEAR(a["articulation"]["failure_rate_pct"].get<double>(), 100.0 / 3, 1e-9);
  EXPECT_NEAR(a["template"]["overall_accuracy_pct"].get<double>(), 200.0 / 3, 1e-9);
  EXPECT_EQ(a["reconstruction"]["parts"], 8);  // 4 parts in each loaded pair
  EXPECT_TRUE(a["mask"].is_null());

  const auto text = run_efc("eval --list " + list);
  EXPECT_EQ(text.exit_code, 0) << text.err;
  for (const char* heading : {"Articulation", "Reconstruction", "Template", "Mask"})
    EXPECT_NE(text.out.find(heading), std::string::npos) << heading << "\n" << text.out;
  EXPECT_NE(text.out.find("66.7"), std::string::npos) << text.out;
}

TEST(EvalCli, BadListLinesAreLocatedErrors) {
  TempDir dir;
  const std::string list = dir.write("pairs.txt", kLamp + " " + kLamp + "\nonly_one_column\n");
  const auto r = run_efc("eval --list " + list);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(list + ":2:1: error[E1021]"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(run_efc("eval --list " + dir.path("absent.txt")).exit_code, 2);
}

TEST(EvalCli, UsageErrorsExitTwo) {
  EXPECT_EQ(run_efc("eval --pred " + kLamp).exit_code, 2);
  EXPECT_EQ(run_efc("eval").exit_code, 2);
  EXPECT_EQ(run_efc("eval --list x --pred " + kLamp + " --gt " + kLamp).exit_code, 2);
  EXPECT_EQ(run_efc("eval --pred " + kLamp + " --gt " + kLamp + " --gt-seq x").exit_code, 2);
}

// A one-frame 4x2 sequence with masks for the head and the switch.
void write_mask(const std::string& path, const std::vector<uint8_t>& pixels) {
  fs::create_directories(fs::path(path).parent_path());
  efc::seq::Image8 img{4, 2, 1, pixels};
  std::string error;
  ASSERT_TRUE(efc::seq::write_png_gray8(path, img, &error)) << error;
}

TEST(EvalCli, MasksAreScoredAndGateTheTemplates) {
  TempDir dir;
  fs::create_directories(dir.path("seq"));
  dir.write("seq/meta.json",
            "{\"efc_sequence\": 1, \"fps\": 30, \"width\": 4, \"height\": 2, "
            "\"intrinsics\": {\"fx\": 4, \"fy\": 4, \"cx\": 2, \"cy\": 1}, \"frames\": 1}\n");
  write_mask(dir.path("seq/masks/switch/000000.png"), {255, 255, 0, 0, 0, 0, 0, 0});
  write_mask(dir.path("seq/masks/bulb/000000.png"), {0, 0, 0, 0, 255, 255, 255, 255});
  write_mask(dir.path("pred/masks/switch/000000.png"), {255, 255, 0, 0, 0, 0, 0, 0});  // IoU 1
  write_mask(dir.path("pred/masks/bulb/000000.png"), {0, 0, 0, 0, 255, 0, 0, 0});      // IoU 0.25
  const json r = eval_json("--pred " + kLamp + " --gt " + kLamp + " --pred-masks " + dir.path("pred") +
                           " --gt-seq " + dir.path("seq"));
  ASSERT_EQ(r["masks"].size(), 2u);
  for (const json& m : r["masks"])
    EXPECT_DOUBLE_EQ(m["mean_iou"].get<double>(), m["part"] == "switch" ? 1.0 : 0.25) << m;
  EXPECT_TRUE(r["functions"][0]["correct"].get<bool>());
  EXPECT_FALSE(r["functions"][0]["masks_ok"].get<bool>());  // the bulb's mask misses

  const std::string list = dir.write("pairs.txt", kLamp + " " + kLamp + " pred seq\n");
  const json l = eval_json("--list " + list);
  EXPECT_DOUBLE_EQ(l["aggregate"]["template"]["overall_accuracy_pct"].get<double>(), 100);
  EXPECT_DOUBLE_EQ(l["aggregate"]["template"]["gated"]["overall_accuracy_pct"].get<double>(), 0);
  EXPECT_DOUBLE_EQ(l["aggregate"]["mask"]["mean_iou"].get<double>(), 0.625);
  EXPECT_DOUBLE_EQ(l["aggregate"]["mask"]["success_rate_pct"].get<double>(), 50);
}

}  // namespace
