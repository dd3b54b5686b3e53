// efc import-egofun3d end to end on a small dataset the test writes in the
// EgoFun3D layout (tests/egofun3d_dataset.h): the real importer program,
// directly and through `efc import-egofun3d`, then every written file read
// back and compared with what was encoded; bad inputs are located errors
// that leave nothing behind for their video.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "compiler/core/load.h"
#include "sequence/sequence.h"
#include "tests/efc_cli.h"
#include "tests/egofun3d_dataset.h"

namespace {

namespace fs = std::filesystem;
using namespace egofun3d_test;
using efc_test::CliResult;

// Runs build/efc-import-egofun3d (or, with via_efc, build/efc import-egofun3d).
CliResult run_importer(const std::string& args, bool via_efc = false) {
  if (via_efc) return efc_test::run_efc("import-egofun3d " + args);
  const fs::path dir = fs::temp_directory_path() / ("efc-ego-run-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string cmd = std::string(EFC_BINARY_DIR) + "/efc-import-egofun3d " + args + " >" +
                          (dir / "out").string() + " 2>" + (dir / "err").string() + " </dev/null";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.signaled = WIFSIGNALED(status) || r.exit_code > 128;
  r.out = efc_test::read_file(dir / "out");
  r.err = efc_test::read_file(dir / "err");
  fs::remove_all(dir);
  return r;
}

class EgoFun3DImport : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("efc-egofun3d-" + std::to_string(getpid()) + "-" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  std::string q(const fs::path& p) const { return "'" + p.string() + "'"; }
  // Entries of OUT (hidden staging folders included).
  std::vector<std::string> listing(const fs::path& out) const {
    std::vector<std::string> names;
    if (fs::exists(out))
      for (const auto& e : fs::directory_iterator(out)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path root_;
};

// The quaternion (x y z w) of a rotation matrix, for comparing poses.txt
// with the extrinsics: built independently of the importer (via the axis
// and angle the test used).
std::array<double, 4> expected_quaternion(int t) {
  const double angle = 0.3 + 0.2 * t;
  double ax = 0.3, ay = -0.5, az = 0.8;
  const double n = std::sqrt(ax * ax + ay * ay + az * az);
  const double s = std::sin(angle / 2);
  return {ax / n * s, ay / n * s, az / n * s, std::cos(angle / 2)};
}

void check_sequence_valid(const fs::path& seq_dir) {
  efc::Diagnostics diags;
  efc::seq::Sequence s;
  ASSERT_TRUE(s.open(seq_dir.string(), diags));
  EXPECT_TRUE(s.check_all(diags));
  std::ostringstream ss;
  diags.print(ss, false);
  EXPECT_FALSE(diags.has_errors()) << ss.str();
  EXPECT_FALSE(s.has_depth()) << "EgoFun3D has no depth; the importer must not invent it";
  EXPECT_TRUE(s.has_poses());
  EXPECT_TRUE(s.has_truth());
}

TEST_F(EgoFun3DImport, ImportsEveryVideoWithTruth) {
  const fs::path ds = root_ / "dataset", out = root_ / "out";
  ASSERT_TRUE(write_dataset(ds)) << "libavcodec has no FFV1 encoder";
  const CliResult r = run_importer(q(ds) + " -o " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("import: 1/2 kitchen_01: 6 frames 32x24"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("import: 2/2 lamp 02: 6 frames 24x18 (cropped)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("has no depth"), std::string::npos) << r.err;
  EXPECT_EQ(listing(out), (std::vector<std::string>{"kitchen_01", "lamp_02"}));

  for (int video = 0; video < 2; ++video) {
    SCOPED_TRACE(video);
    const fs::path seq_dir = out / (video == 0 ? "kitchen_01" : "lamp_02");
    check_sequence_valid(seq_dir);
    efc::Diagnostics diags;
    efc::seq::Sequence s;
    ASSERT_TRUE(s.open(seq_dir.string(), diags));
    const efc::seq::Meta& m = s.meta();
    const bool cropped = video == 1;
    const int w = cropped ? kCropX1 - kCropX0 : kOrigW, h = cropped ? kCropY1 - kCropY0 : kOrigH;
    const int x0 = cropped ? kCropX0 : 0, y0 = cropped ? kCropY0 : 0;
    EXPECT_EQ(m.frames, kFrames);
    EXPECT_EQ(m.width, w);
    EXPECT_EQ(m.height, h);
    EXPECT_NEAR(m.fps, 10, 1e-9);
    EXPECT_EQ(m.source, "egofun3d");
    EXPECT_DOUBLE_EQ(m.intrinsics.fx, 20);
    EXPECT_DOUBLE_EQ(m.intrinsics.fy, 21);
    EXPECT_DOUBLE_EQ(m.intrinsics.cx, cropped ? 11.5 : 15.5);
    EXPECT_DOUBLE_EQ(m.intrinsics.cy, cropped ? 9.5 : 11.5);
    using Parts = std::vector<std::pair<std::string, std::string>>;
    if (video == 0) {
      // HDF5 groups come in name order, as h5py lists them.
      EXPECT_EQ(m.parts, (Parts{{"drawer", "effector"}, {"kitchen_cabinet", "object"}, {"stove_knob", "receptor"}}));
      ASSERT_EQ(m.functions.size(), 1u);
      EXPECT_EQ(m.functions[0].name, "f7");
      EXPECT_EQ(m.functions[0].receptor, "stove_knob");
      EXPECT_EQ(m.functions[0].effector, "drawer");
    } else {
      EXPECT_EQ(m.parts, (Parts{{"bulb", "effector"}, {"button", "receptor"}}));
      ASSERT_EQ(m.functions.size(), 1u);
      EXPECT_EQ(m.functions[0].name, "f12");
      ASSERT_TRUE(m.extra.contains("x-egofun3d"));
      EXPECT_EQ(m.extra["x-egofun3d"]["crop_box"], (nlohmann::json{kCropX0, kCropY0, kCropX1, kCropY1}));
    }

    // Pixels: FFV1 RGB is lossless, so the decoded frames are what was encoded.
    for (int t = 0; t < kFrames; ++t) {
      efc::seq::Image8 img;
      ASSERT_TRUE(s.read_rgb(t, diags, &img));
      int worst = 0;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const auto want = pixel(video, x + x0, y + y0, t);
          for (int c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(int(img.pixels[(size_t(y) * w + x) * 3 + c]) - int(want[c])));
        }
      EXPECT_LE(worst, 1) << "frame " << t;
    }
    // Masks: exact, cropped out of the full-frame HDF5 masks.
    const std::vector<std::pair<std::string, int>> mask_parts =
        video == 0 ? std::vector<std::pair<std::string, int>>{{"stove_knob", 0}, {"drawer", 1}, {"kitchen_cabinet", 2}}
                   : std::vector<std::pair<std::string, int>>{{"button", 0}, {"bulb", 1}};
    for (const auto& [name, part] : mask_parts)
      for (int t = 0; t < kFrames; ++t) {
        efc::seq::Image8 img;
        ASSERT_TRUE(s.read_mask(name, t, diags, &img)) << name;
        int wrong = 0, inside = 0;
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const bool want = mask_at(part, x + x0, y + y0, t);
            inside += want;
            wrong += want != (img.pixels[size_t(y) * w + x] != 0);
          }
        EXPECT_EQ(wrong, 0) << name << " frame " << t;
        EXPECT_GT(inside, 0) << name << " frame " << t;
      }
    // Poses: the extrinsics, t = i / fps.
    std::vector<efc::seq::Pose> poses;
    ASSERT_TRUE(s.read_poses(diags, &poses));
    ASSERT_EQ(poses.size(), size_t(kFrames));
    for (int t = 0; t < kFrames; ++t) {
      const auto c = camera(t);
      EXPECT_NEAR(poses[t].t, t / 10.0, 1e-12);
      EXPECT_NEAR(poses[t].p[0], c[3], 1e-12);
      EXPECT_NEAR(poses[t].p[1], c[7], 1e-12);
      EXPECT_NEAR(poses[t].p[2], c[11], 1e-12);
      const auto want = expected_quaternion(t);
      const double sign = (want[3] * poses[t].q[3] >= 0) ? 1 : -1;
      for (int k = 0; k < 4; ++k) EXPECT_NEAR(poses[t].q[k], sign * want[k], 1e-9) << "frame " << t;
    }
    // truth/: a spec the compiler accepts, in the extrinsics' world frame.
    const fs::path spec_path = seq_dir / "truth/spec.json";
    efc::Diagnostics spec_diags;
    const auto obj = efc::load_spec(spec_path.string(), efc::LoadOptions{}, spec_diags);
    ASSERT_TRUE(obj.has_value());
    const nlohmann::json spec = nlohmann::json::parse(efc_test::read_file(spec_path));
    const nlohmann::json pose = nlohmann::json::parse(efc_test::read_file(seq_dir / "truth/object_pose.json"));
    EXPECT_EQ(pose["object_to_world"], (nlohmann::json{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}));
    ASSERT_EQ(spec["parts"].size(), 3u);
    EXPECT_EQ(spec["parts"][0]["name"], "base");
    EXPECT_FALSE(spec["parts"][0].contains("joint"));
    const auto& receptor = spec["parts"][1];
    const auto& effector = spec["parts"][2];
    ASSERT_EQ(spec["functions"].size(), 1u);
    const auto& f = spec["functions"][0];
    if (video == 0) {
      EXPECT_EQ(spec["name"], "kitchen_01");
      EXPECT_EQ(receptor["name"], "stove_knob");
      EXPECT_EQ(receptor["joint"]["type"], "revolute");
      EXPECT_EQ(receptor["joint"]["axis"], (nlohmann::json{0, 1, 0}));
      EXPECT_EQ(receptor["joint"]["origin"], (nlohmann::json{0.275, 0.42, 0.375}));
      EXPECT_EQ(receptor["joint"]["range"], (nlohmann::json{0, 1.5}));
      EXPECT_EQ(effector["name"], "drawer");
      EXPECT_EQ(effector["joint"]["type"], "prismatic");
      EXPECT_EQ(effector["joint"]["axis"], (nlohmann::json{0, 1, 0}));  // normalised from [0, 2, 0]
      EXPECT_EQ(effector["joint"]["range"], (nlohmann::json{0, 0.3}));
      EXPECT_EQ(f["name"], "f7");
      EXPECT_EQ(f["mapping"]["type"], "linear");
      EXPECT_EQ(f["effect"]["type"], "geometry");
      // A mesh per part, cut from the PLY's faces: 8 vertices, 12 triangles.
      for (const char* part : {"base", "stove_knob", "drawer"}) {
        const std::string objt = efc_test::read_file(seq_dir / "truth/meshes" / (std::string(part) + ".obj"));
        size_t v = 0, fc = 0;
        std::istringstream ls(objt);
        for (std::string line; std::getline(ls, line);) v += line.rfind("v ", 0) == 0, fc += line.rfind("f ", 0) == 0;
        EXPECT_EQ(v, 8u) << part;
        EXPECT_EQ(fc, 12u) << part;
      }
      EXPECT_EQ(receptor["geometry"]["mesh"], "meshes/stove_knob.obj");
    } else {
      EXPECT_EQ(spec["name"], "lamp_02");
      EXPECT_EQ(receptor["name"], "button");
      EXPECT_EQ(receptor["joint"]["type"], "prismatic");  // "translation"
      EXPECT_EQ(receptor["joint"]["axis"], (nlohmann::json{0, -1, 0}));
      EXPECT_EQ(effector["joint"]["type"], "fixed");  // no articulation entry
      EXPECT_EQ(f["mapping"]["type"], "binary");
      EXPECT_EQ(f["effect"]["type"], "illumination");
      // A point cloud has no faces: boxes around the points, and a note.
      ASSERT_TRUE(receptor["geometry"].contains("box"));
      const auto& box = receptor["geometry"]["box"];
      EXPECT_NEAR(box["size"][0].get<double>(), 0.05, 1e-9);
      EXPECT_NEAR(box["center"][1].get<double>(), 0.415, 1e-9);
      EXPECT_FALSE(fs::exists(seq_dir / "truth/meshes"));
      EXPECT_NE(r.err.find("note: part 'button': the PLY is a point cloud"), std::string::npos) << r.err;
    }
  }

  // Through the efc program: the same folders, and JSON lines on request.
  const fs::path out2 = root_ / "out2";
  const CliResult r2 = run_importer(q(ds) + " -o " + q(out2) + " --diagnostics-format json", true);
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  std::istringstream lines(r2.err);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) {
      EXPECT_TRUE(nlohmann::json::accept(line)) << line;
    }
  for (const char* name : {"kitchen_01", "lamp_02"}) {
    EXPECT_EQ(efc_test::read_file(out / name / "meta.json"), efc_test::read_file(out2 / name / "meta.json"));
    EXPECT_EQ(efc_test::read_file(out / name / "truth/spec.json"), efc_test::read_file(out2 / name / "truth/spec.json"));
    EXPECT_EQ(efc_test::read_file(out / name / "rgb/000003.png"), efc_test::read_file(out2 / name / "rgb/000003.png"));
  }
  // Importing again replaces the folders.
  const CliResult r3 = run_importer(q(ds) + " -o " + q(out));
  EXPECT_EQ(r3.exit_code, 0) << r3.err;
  EXPECT_EQ(listing(out), (std::vector<std::string>{"kitchen_01", "lamp_02"}));
}

TEST_F(EgoFun3DImport, MissingMetadataIsAnUnreadableFile) {
  const fs::path out = root_ / "out";
  fs::create_directories(root_ / "empty");
  const CliResult r = run_importer(q(root_ / "empty") + " -o " + q(out));
  EXPECT_FALSE(r.signaled);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("empty/dataset_metadata.json: error[E1040]: does not exist"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(EgoFun3DImport, MalformedMetadataIsLocated) {
  const fs::path ds = root_ / "dataset", out = root_ / "out";
  write_text(ds / "dataset_metadata.json", "[\n  {\"video_name\": \"a\",\n   \"source\": }\n]\n");
  const CliResult r = run_importer(q(ds) + " -o " + q(out));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("dataset_metadata.json:3:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("error[E0003]"), std::string::npos) << r.err;
  EXPECT_TRUE(listing(out).empty());

  // An entry with a key of the wrong type: located at the value.
  write_text(ds / "dataset_metadata.json", "[\n  {\"video_name\": 5}\n]\n");
  const CliResult r2 = run_importer(q(ds) + " -o " + q(out));
  EXPECT_EQ(r2.exit_code, 1) << r2.err;
  EXPECT_NE(r2.err.find("dataset_metadata.json:2:18: error[E1040]: \"video_name\" must be a string"),
            std::string::npos)
      << r2.err;
  EXPECT_TRUE(listing(out).empty());
}

// One broken input of one video: a located error, exit 1, nothing written for
// that video, the other video imported.
struct BadCase {
  const char* name;
  Faults faults;
  const char* failed;    // the video that fails ("" = both)
  const char* expected;  // in stderr
};

TEST_F(EgoFun3DImport, BadInputsFailTheirVideoOnly) {
  Faults npy, h5, video, json_syntax, unarticulated;
  npy.npy_wrong_shape = true;
  h5.h5_t_mismatch = true;
  video.missing_video = true;
  json_syntax.bad_function_json = true;
  unarticulated.receptor_unarticulated = true;
  const BadCase cases[] = {
      {"npy", npy, "kitchen_01", "cameras/kitchen_01/extrinsics.npy:1:"},
      {"h5", h5, "kitchen_01", "masks/kitchen_01.h5: error[E1044]: group 'drawer': masks has 5 frames (T), the video has 6"},
      {"video", video, "lamp_02", "videos/lamp_02_cropped.avi: error[E1041]: the video does not exist"},
      {"json", json_syntax, "", "annotations/functions.json:2:53: error[E0003]"},
      {"unarticulated", unarticulated, "kitchen_01", "error[E1047]: video 'kitchen_01': the truth spec"},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path ds = root_ / (std::string("ds-") + c.name), out = root_ / (std::string("out-") + c.name);
    ASSERT_TRUE(write_dataset(ds, c.faults));
    const CliResult r = run_importer(q(ds) + " -o " + q(out));
    EXPECT_FALSE(r.signaled);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
    std::vector<std::string> want;
    if (std::string(c.failed) == "kitchen_01") want = {"lamp_02"};
    if (std::string(c.failed) == "lamp_02") want = {"kitchen_01"};
    EXPECT_EQ(listing(out), want) << "a failed video leaves nothing, not even a staging folder";
    for (const std::string& name : want) check_sequence_valid(out / name);
  }
}

TEST_F(EgoFun3DImport, EfcReportsAMissingImporter) {
  // A copy of efc alone in a folder: no efc-import-egofun3d beside it.
  const fs::path lonely = root_ / "bin";
  fs::create_directories(lonely);
  fs::copy_file(fs::path(EFC_BINARY_DIR) / "efc", lonely / "efc");
  const std::string cmd = "'" + (lonely / "efc").string() + "' import-egofun3d x -o y 2>'" +
                          (root_ / "err").string() + "'";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  const std::string err = efc_test::read_file(root_ / "err");
  EXPECT_NE(err.find("error[E1049]"), std::string::npos) << err;
  EXPECT_NE(err.find("--target efc-import-egofun3d"), std::string::npos) << err;
}

}  // namespace
