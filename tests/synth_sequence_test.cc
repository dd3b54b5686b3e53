// `efc synth` end to end on real examples: the sequence's depth, masks,
// poses and intrinsics agree with the true geometry; the truth agrees with
// `efc play`; the same seed gives the same bytes; what is written reads back
// unchanged.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "backends/common/temp_dir.h"
#include "compiler/core/load.h"
#include "harness/play.h"
#include "harness/playback.h"
#include "sequence/sequence.h"
#include "synth/synth.h"

namespace fs = std::filesystem;

namespace efc {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Object load_example(const std::string& name) {
  Diagnostics diags;
  std::optional<Object> obj = load_spec(std::string(EFC_SOURCE_DIR) + "/examples/" + name + ".json", {}, diags);
  EXPECT_TRUE(obj.has_value());
  return *obj;
}

// Synthesises `obj` (the example `example`, maybe changed) into
// dir/<example>_<seed> and returns the folder.
std::string make_sequence_of(const Object& obj, const fs::path& dir, const std::string& example,
                             const std::string& spec_json, synth::NoiseLevel noise, uint64_t seed, int frames,
                             int width, int height, const std::string& profile) {
  synth::SynthOptions opts;
  opts.frames = frames;
  opts.width = width;
  opts.height = height;
  opts.seed = seed;
  opts.knobs.noise = noise;
  opts.threads = 2;
  opts.spec_json = spec_json;
  std::string error;
  int line = 0;
  bool io = false;
  EXPECT_TRUE(parse_profile(profile, &opts.profile, &error, &line, &io)) << error;
  Diagnostics diags;
  const std::string out = (dir / (example + "_" + std::to_string(seed))).string();
  EXPECT_EQ(synth::synthesize(obj, opts, out, diags, nullptr), 0);
  for (const Diagnostic& d : diags.items()) ADD_FAILURE() << format_text(d);
  return out;
}

// Synthesises `example` into dir/<example>_<seed> and returns the folder.
std::string make_sequence(const fs::path& dir, const std::string& example, synth::NoiseLevel noise,
                          uint64_t seed, int frames, int width, int height, const std::string& profile = "sweep") {
  return make_sequence_of(load_example(example), dir, example,
                          read_file(std::string(EFC_SOURCE_DIR) + "/examples/" + example + ".json"), noise, seed,
                          frames, width, height, profile);
}

Isometry3d object_to_world(const std::string& seq) {
  const nlohmann::json j = nlohmann::json::parse(read_file(seq + "/truth/object_pose.json"));
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) M(r, c) = j["object_to_world"][4 * r + c].get<double>();
  Isometry3d T;
  T.matrix() = M;
  return T;
}

Isometry3d pose_matrix(const seq::Pose& p) {
  Isometry3d T = Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(p.q[3], p.q[0], p.q[1], p.q[2]).normalized().toRotationMatrix();
  T.translation() = Vector3d(p.p[0], p.p[1], p.p[2]);
  return T;
}

std::vector<std::map<std::string, double>> read_csv_rows(const std::string& path) {
  std::ifstream in(path);
  std::string header, line;
  std::getline(in, header);
  std::vector<std::string> cols;
  std::stringstream hs(header);
  for (std::string c; std::getline(hs, c, ',');) cols.push_back(c);
  std::vector<std::map<std::string, double>> rows;
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::map<std::string, double> row;
    size_t i = 0;
    for (std::string v; std::getline(ls, v, ','); ++i) row[cols.at(i)] = std::stod(v);
    rows.push_back(row);
  }
  return rows;
}

// Distance from p (world of the model) to the surface of geom g.
double surface_distance(const mjModel* m, const mjData* d, int g, const Vector3d& p) {
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = d->geom_xmat[9 * g + 3 * r + c];
  const Vector3d q = R.transpose() * (p - Vector3d(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]));
  const double* s = m->geom_size + 3 * g;
  switch (m->geom_type[g]) {
    case mjGEOM_SPHERE:
      return std::fabs(q.norm() - s[0]);
    case mjGEOM_BOX: {
      const Vector3d e = q.cwiseAbs() - Vector3d(s[0], s[1], s[2]);
      return std::fabs(e.cwiseMax(0.0).norm() + std::min(e.maxCoeff(), 0.0));
    }
    case mjGEOM_CYLINDER: {
      const double dr = std::hypot(q.x(), q.y()) - s[0], dz = std::fabs(q.z()) - s[1];
      return std::fabs(std::min(std::max(dr, dz), 0.0) + std::hypot(std::max(dr, 0.0), std::max(dz, 0.0)));
    }
    case mjGEOM_CAPSULE: {
      const double z = std::clamp(q.z(), -s[1], s[1]);
      return std::fabs((q - Vector3d(0, 0, z)).norm() - s[0]);
    }
    default:
      return 1e9;  // meshes: not used by the parts these tests look at
  }
}

// The object posed as truth/joints.csv says at `row`, in the object frame.
struct PosedObject {
  Playback run;
  explicit PosedObject(const Object& obj) {
    Diagnostics diags;
    Profile hold;
    hold.kind = Profile::Kind::Hold;
    hold.hold_at = Profile::HoldAt::Lo;
    EXPECT_EQ(run.open(obj, hold, 1.0, 0.002, diags), 0);
  }
  void pose(const std::map<std::string, double>& joints) {
    for (const auto& [name, q] : joints) {
      const int j = mj_name2id(run.model(), mjOBJ_JOINT, name.c_str());
      if (j >= 0) run.data()->qpos[run.model()->jnt_qposadr[j]] = q;
    }
    mj_kinematics(run.model(), run.data());
  }
  double distance_to_part(const std::string& part, const Vector3d& p) {
    const mjModel* m = run.model();
    const int b = mj_name2id(m, mjOBJ_BODY, part.c_str());
    double best = 1e9;
    for (int g = m->body_geomadr[b]; g >= 0 && g < m->body_geomadr[b] + m->body_geomnum[b]; ++g)
      best = std::min(best, surface_distance(m, run.data(), g, p));
    return best;
  }
};

class SynthSequence : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir("efc-synth-test");
    stove_ = new std::string(make_sequence(dir_->path(), "stove", synth::NoiseLevel::None, 7, 36, 320, 240));
  }
  static void TearDownTestSuite() {
    delete stove_;
    delete dir_;
  }
  static TempDir* dir_;
  static std::string* stove_;
};
TempDir* SynthSequence::dir_ = nullptr;
std::string* SynthSequence::stove_ = nullptr;

// Every pixel of a part's mask, back-projected with the intrinsics, its depth
// and the true camera pose, lies on that part's true surface (within 2 mm);
// and every pixel that lies on a part's surface carries that part's mask.
TEST_F(SynthSequence, BackProjectedMaskPixelsLieOnTheirPartsSurface) {
  seq::Sequence s;
  Diagnostics diags;
  ASSERT_TRUE(s.open(*stove_, diags));
  std::vector<seq::Pose> poses;
  ASSERT_TRUE(seq::read_poses(*stove_ + "/truth/poses.txt", diags, &poses));
  const auto joints = read_csv_rows(*stove_ + "/truth/joints.csv");
  const Isometry3d world_to_object = object_to_world(*stove_).inverse();
  const seq::Intrinsics& K = s.meta().intrinsics;
  const Object obj = load_example("stove");
  PosedObject posed(obj);
  const std::vector<std::string> parts = {"knob_left", "knob_right", "body", "burner_left"};
  std::map<std::string, int> checked;
  int labelled_elsewhere = 0, on_surface = 0;
  for (int f = 0; f < s.meta().frames; f += 5) {
    posed.pose(joints[f]);
    seq::Image16 depth;
    ASSERT_TRUE(s.read_depth(f, diags, &depth));
    std::map<std::string, seq::Image8> masks;
    for (const std::string& p : parts) ASSERT_TRUE(s.read_mask(p, f, diags, &masks[p]));
    ASSERT_TRUE(s.read_mask("hand", f, diags, &masks["hand"]));
    const Isometry3d cam = world_to_object * pose_matrix(poses[f]);
    for (int v = 0; v < depth.height; ++v)
      for (int u = 0; u < depth.width; ++u) {
        const size_t i = static_cast<size_t>(v) * depth.width + u;
        if (depth.pixels[i] == 0) continue;
        const double z = depth.pixels[i] * s.meta().depth_scale;
        const Vector3d p = cam * Vector3d((u - K.cx) / K.fx * z, (v - K.cy) / K.fy * z, z);
        for (const std::string& part : parts) {
          const double dist = posed.distance_to_part(part, p);
          if (masks[part].pixels[i]) {
            // 1 mm of quantisation plus the step between a frame's joints
            // and the mm-rounded depth.
            EXPECT_LT(dist, 0.002) << part << " frame " << f << " pixel " << u << "," << v;
            checked[part]++;
          } else if (dist < 0.0005 && part.rfind("knob", 0) == 0) {
            on_surface++;
            bool other = false;
            for (const auto& [name, mask] : masks) other |= mask.pixels[i] != 0;
            if (!other) labelled_elsewhere++;
          }
        }
      }
  }
  EXPECT_GT(checked["knob_left"], 20);
  EXPECT_GT(checked["body"], 1000);
  EXPECT_EQ(labelled_elsewhere, 0) << "of " << on_surface << " pixels on a knob's surface";
}

// truth/joints.csv and truth/effects.csv are what `efc play` logs when it
// follows truth/profile.csv, number for number.
TEST_F(SynthSequence, TruthEqualsEfcPlay) {
  const Object obj = load_example("stove");
  PlayOptions opts;
  std::string error;
  int line = 0;
  bool io = false;
  ASSERT_TRUE(parse_profile("csv:" + *stove_ + "/truth/profile.csv", &opts.profile, &error, &line, &io)) << error;
  opts.duration = 36 / 30.0;
  Diagnostics diags;
  PlayLog log;
  ASSERT_EQ(play(obj, opts, diags, &log), 0);
  const auto joints = read_csv_rows(*stove_ + "/truth/joints.csv");
  const auto effects = read_csv_rows(*stove_ + "/truth/effects.csv");
  ASSERT_EQ(joints.size(), 36u);
  auto col = [&](const std::string& name) {
    for (size_t i = 0; i < log.columns.size(); ++i)
      if (log.columns[i] == name) return static_cast<int>(i);
    return -1;
  };
  auto g9 = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return std::string(buf);
  };
  int compared = 0;
  for (size_t f = 0; f < joints.size(); ++f) {
    const auto& row = log.rows.at(std::lround(f / 30.0 / 0.002));
    EXPECT_EQ(g9(row[col("heat_left.s_R")]), g9(joints[f].at("knob_left"))) << f;
    EXPECT_EQ(g9(row[col("heat_right.s_R")]), g9(joints[f].at("knob_right"))) << f;
    for (const char* fn : {"heat_left", "heat_right", "hob_on"})
      EXPECT_EQ(g9(row[col(std::string(fn) + ".s_E")]), g9(effects[f].at(std::string(fn) + ".s_E"))) << f << fn;
    compared += 5;
  }
  EXPECT_EQ(compared, 180);
  // The knobs really turn and the hob heats up: the comparison is not of constants.
  EXPECT_GT(joints[25].at("knob_left") + joints[25].at("knob_right"), 0.5);
}

// Noise none: the recorded poses are the true ones; poses.txt has one line per frame.
TEST_F(SynthSequence, TheSequenceChecksAndReadsBackUnchanged) {
  seq::Sequence s;
  Diagnostics diags;
  ASSERT_TRUE(s.open(*stove_, diags));
  EXPECT_TRUE(s.check_all(diags));
  for (const Diagnostic& d : diags.items()) ADD_FAILURE() << format_text(d);
  EXPECT_EQ(s.meta().frames, 36);
  EXPECT_EQ(s.meta().width, 320);
  EXPECT_TRUE(s.has_depth() && s.has_poses() && s.has_hands() && s.has_truth());
  // Written again through the library: the same bytes.
  TempDir copy("efc-synth-copy");
  const std::string out = copy.path().string();
  std::string error;
  ASSERT_TRUE(seq::write_meta(out + "/meta.json", s.meta(), &error)) << error;
  EXPECT_EQ(read_file(out + "/meta.json"), read_file(*stove_ + "/meta.json"));
  std::vector<seq::Pose> poses;
  std::vector<seq::HandPoint> hands;
  ASSERT_TRUE(s.read_poses(diags, &poses));
  ASSERT_TRUE(s.read_hands(diags, &hands));
  ASSERT_TRUE(seq::write_poses(out + "/poses.txt", poses, &error));
  ASSERT_TRUE(seq::write_hands(out + "/hands.txt", hands, &error));
  EXPECT_EQ(read_file(out + "/poses.txt"), read_file(*stove_ + "/poses.txt"));
  EXPECT_EQ(read_file(out + "/hands.txt"), read_file(*stove_ + "/hands.txt"));
  for (int f : {0, 17, 35}) {
    seq::Image8 rgb, mask;
    seq::Image16 depth;
    ASSERT_TRUE(s.read_rgb(f, diags, &rgb));
    ASSERT_TRUE(s.read_depth(f, diags, &depth));
    ASSERT_TRUE(s.read_mask("hand", f, diags, &mask));
    const int level = synth::SynthOptions().png_compression;  // what synth wrote with
    ASSERT_TRUE(seq::write_png_rgb(out + "/rgb.png", rgb, &error, level));
    ASSERT_TRUE(seq::write_png_gray16(out + "/depth.png", depth, &error, level));
    ASSERT_TRUE(seq::write_png_gray8(out + "/mask.png", mask, &error, level));
    EXPECT_TRUE(read_file(out + "/rgb.png") == read_file(s.rgb_path(f))) << f;
    EXPECT_TRUE(read_file(out + "/depth.png") == read_file(s.depth_path(f))) << f;
    EXPECT_TRUE(read_file(out + "/mask.png") == read_file(s.mask_path("hand", f))) << f;
  }
  // The hand is seen while it works the knobs.
  int seen = 0;
  for (const seq::HandPoint& h : hands) seen += h.seen;
  EXPECT_GT(seen, 10);
}

// The head camera keeps the object in the picture: in every frame some of
// it is seen, and its centre stays inside the middle 80% of the image.
TEST_F(SynthSequence, TheObjectStaysInView) {
  seq::Sequence s;
  Diagnostics diags;
  ASSERT_TRUE(s.open(*stove_, diags));
  for (int f = 0; f < s.meta().frames; ++f) {
    double n = 0, sx = 0, sy = 0;
    for (const auto& [part, role] : s.meta().parts) {
      if (role == "hand") continue;
      seq::Image8 mask;
      ASSERT_TRUE(s.read_mask(part, f, diags, &mask));
      for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x)
          if (mask.pixels[static_cast<size_t>(y) * mask.width + x]) n += 1, sx += x, sy += y;
    }
    ASSERT_GT(n, 0.01 * s.meta().width * s.meta().height) << "frame " << f;
    EXPECT_GT(sx / n, 0.1 * s.meta().width) << f;
    EXPECT_LT(sx / n, 0.9 * s.meta().width) << f;
    EXPECT_GT(sy / n, 0.1 * s.meta().height) << f;
    EXPECT_LT(sy / n, 0.9 * s.meta().height) << f;
  }
}

std::map<std::string, std::string> folder_bytes(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = read_file(e.path());
  return files;
}

// A lamp's bulb looks lit while its light is on and unlit while it is off,
// whichever way its range runs: a white bulb is no brighter lit than unlit
// unless the unlit glass is grey, and a press that dims ([450, 0]) must take
// it dark, not light it. (The examples' bulbs hide under shades and hoods at
// a test's resolution: a box with a bulb on its front and a button.)
TEST(SynthLampGlow, TheBulbIsBrighterWhileTheLightIsOn) {
  TempDir dir("efc-synth-glow");
  for (const bool dimming : {false, true}) {
    const std::string range = dimming ? "[450, 0]" : "[0, 450]";
    const std::string spec = R"({"efc": 1, "name": "glow", "parts": [
      {"name": "body", "geometry": {"box": {"size": [0.3, 0.2, 0.2], "center": [0, 0, 0.1]}}, "rgba": [0.3, 0.3, 0.3, 1]},
      {"name": "bulb", "geometry": {"sphere": {"radius": 0.05, "center": [0.07, -0.1, 0.12]}},
       "rgba": [1, 0.95, 0.85, 1], "joint": {"type": "fixed", "parent": "body"}},
      {"name": "button", "geometry": {"box": {"size": [0.05, 0.02, 0.05], "center": [-0.08, -0.11, 0.12]}},
       "joint": {"type": "prismatic", "parent": "body", "axis": [0, 1, 0], "range": [0, 0.01],
                 "spring": {"stiffness": 80, "rest": 0}}}],
      "functions": [{"name": "light", "receptor": "button", "effector": "bulb", "mapping": {"type": "binary"},
                     "effect": {"type": "illumination", "range": )" + range + R"(}}]})";
    const fs::path spec_path = dir.path() / (dimming ? "dim.json" : "lit.json");
    std::ofstream(spec_path) << spec;
    Diagnostics load_diags;
    std::optional<Object> obj = load_spec(spec_path.string(), {}, load_diags);
    ASSERT_TRUE(obj.has_value());
    const std::string seq = make_sequence_of(*obj, dir.path() / (dimming ? "dim" : "lit"), "glow", spec,
                                             synth::NoiseLevel::None, 1, 40, 160, 120, "sweep");
    seq::Sequence s;
    Diagnostics diags;
    ASSERT_TRUE(s.open(seq, diags));
    const auto effects = read_csv_rows(seq + "/truth/effects.csv");
    double sum[2] = {0, 0};
    int frames[2] = {0, 0};
    for (int f = 0; f < static_cast<int>(effects.size()); ++f) {
      const double lumens = effects[f].at("light.s_E");
      if (lumens != 0 && lumens != 450) continue;
      seq::Image8 rgb, mask;
      ASSERT_TRUE(s.read_rgb(f, diags, &rgb));
      ASSERT_TRUE(s.read_mask("bulb", f, diags, &mask));
      double luminance = 0;
      int pixels = 0;
      for (int i = 0; i < rgb.width * rgb.height; ++i) {
        if (!mask.pixels[i]) continue;
        const uint8_t* c = &rgb.pixels[3 * i];
        luminance += (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]) / 255.0;
        ++pixels;
      }
      if (pixels < 4) continue;
      sum[lumens == 450] += luminance / pixels;
      ++frames[lumens == 450];
    }
    ASSERT_GT(frames[0], 3) << range;
    ASSERT_GT(frames[1], 3) << range;
    EXPECT_GT(sum[1] / frames[1], sum[0] / frames[0] + 0.2) << range << ": lit " << sum[1] / frames[1]
                                                           << ", unlit " << sum[0] / frames[0];
  }
}

// The same seed gives the same bytes (noise included, frames written by
// several threads); another seed gives other noise.
TEST(SynthDeterminism, SameSeedSameBytes) {
  TempDir a("efc-synth-a"), b("efc-synth-b");
  const auto first = folder_bytes(make_sequence(a.path(), "kitchen_faucet", synth::NoiseLevel::Realistic, 3, 12, 160, 120));
  const auto again = folder_bytes(make_sequence(b.path(), "kitchen_faucet", synth::NoiseLevel::Realistic, 3, 12, 160, 120));
  ASSERT_GT(first.size(), 50u);
  EXPECT_EQ(first.size(), again.size());
  for (const auto& [name, bytes] : first) EXPECT_TRUE(again.count(name) && again.at(name) == bytes) << name;
  const auto other = folder_bytes(make_sequence(a.path(), "kitchen_faucet", synth::NoiseLevel::Realistic, 4, 12, 160, 120));
  EXPECT_NE(other.at("depth/000005.png"), first.at("depth/000005.png"));
  EXPECT_NE(other.at("poses.txt"), first.at("poses.txt"));
}

}  // namespace
}  // namespace efc
