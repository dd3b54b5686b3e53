// `efc articulate` as a user meets it: exit codes and located errors for
// bad tracks, the JSON it prints, and the hinge it finds from the hand track
// of a synthetic recording (efc synth) against the spec's own joint.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/efc_cli.h"

namespace {

namespace fs = std::filesystem;
using efc_test::run_efc;
using Eigen::Vector3d;

fs::path fresh_dir(const std::string& stem) {
  fs::path p = fs::temp_directory_path() / ("efc-articulate-" + std::to_string(getpid()) + "-" + stem);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

TEST(ArticulateCli, BadInputsAreReportedWithTheirExitCodes) {
  const fs::path dir = fresh_dir("bad");
  std::ofstream(dir / "bad.txt") << "0 0 0\n0.1 0 zero\n0.2 0 0\n";
  auto r = run_efc("articulate --track " + (dir / "bad.txt").string() + " --format xyz");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("bad.txt:2:7: error[E1030]"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_EQ(run_efc("articulate --track " + (dir / "bad.txt").string() + " --format quaternions").exit_code, 2);
  EXPECT_EQ(run_efc("articulate --track " + (dir / "none.txt").string() + " --format xyz").exit_code, 2);
  fs::remove_all(dir);
}

TEST(ArticulateCli, PrintsOneJsonObject) {
  const fs::path dir = fresh_dir("ok");
  {
    std::ofstream out(dir / "slide.txt");
    for (int i = 0; i < 20; ++i) out << 0.02 * i << " 0.5 0.9\n";
  }
  auto r = run_efc("articulate --track " + (dir / "slide.txt").string() + " --format xyz");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["type"], "prismatic");
  EXPECT_NEAR(j["axis"][0].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(j["range"][1].get<double>(), 0.38, 1e-9);
  for (const char* key : {"origin", "residual", "scores"}) EXPECT_TRUE(j.contains(key)) << key;
  fs::remove_all(dir);
}

// The faucet's lever (revolute about the object's y axis through
// (-0.035, 0, 0.215), swept over [0, 0.6] rad): the hand's contact point
// while it holds the lever, taken from a synthetic recording, gives that
// hinge in the world frame.
TEST(ArticulateCli, TheHandTrackOfASyntheticRecordingGivesTheSpecsHinge) {
  const fs::path dir = fresh_dir("synth");
  const std::string seq = (dir / "seq").string();
  auto r = run_efc("synth " + std::string(EFC_SOURCE_DIR) + "/examples/kitchen_faucet.json -o " + seq +
                   " --frames 90 --width 64 --height 48 --noise none --seed 4");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json timeline = nlohmann::json::parse(efc_test::read_file(seq + "/truth/timeline.json"));
  const double grasp = timeline["visits"][0]["grasp"], release = timeline["visits"][0]["release"];
  std::ifstream hands(seq + "/truth/hands.txt");
  std::ofstream held(dir / "held.txt");
  int samples = 0;
  for (std::string line; std::getline(hands, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream in(line);
    double t;
    in >> t;
    if (t >= grasp && t <= release) held << line << "\n", ++samples;
  }
  held.close();
  ASSERT_GT(samples, 20);
  r = run_efc("articulate --track " + (dir / "held.txt").string() + " --format xyz");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["type"], "revolute") << r.out;

  const nlohmann::json pose = nlohmann::json::parse(efc_test::read_file(seq + "/truth/object_pose.json"));
  Eigen::Matrix4d M;
  for (int k = 0; k < 16; ++k) M(k / 4, k % 4) = pose["object_to_world"][k].get<double>();
  const Vector3d axis_world = M.block<3, 3>(0, 0) * Vector3d(0, 1, 0);
  const Vector3d origin_world = M.block<3, 3>(0, 0) * Vector3d(-0.035, 0, 0.215) + M.block<3, 1>(0, 3);
  const Vector3d axis(j["axis"][0], j["axis"][1], j["axis"][2]);
  const Vector3d origin(j["origin"][0], j["origin"][1], j["origin"][2]);
  EXPECT_LT(std::acos(std::min(1.0, std::fabs(axis.dot(axis_world)))), 0.01) << r.out;
  const Vector3d d = origin - origin_world;
  EXPECT_LT((d - d.dot(axis_world) * axis_world).norm(), 0.003) << r.out;
  EXPECT_NEAR(j["range"][1].get<double>() - j["range"][0].get<double>(), 0.6, 0.02) << r.out;
  fs::remove_all(dir);
}

}  // namespace
