// The sequence format (shared/spec/sequence.md): PNG, meta.json, poses and
// hands round trips, a whole folder written and read back unchanged, and
// every kind of bad input reported as a located diagnostic, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <regex>
#include <sstream>
#include <unistd.h>

#include "sequence/sequence.h"

namespace efc::seq {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = (fs::temp_directory_path() /
             ("efc-seq-test-" + std::to_string(getpid()) + "-" + std::to_string(counter++)))
                .string();
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  const std::string& path() const { return path_; }
  std::string operator/(const std::string& rel) const { return (fs::path(path_) / rel).string(); }

 private:
  std::string path_;
};

void write_text(const std::string& path, const std::string& text) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

Image8 rgb_image(int w, int h, unsigned seed) {
  Image8 img{w, h, 3, std::vector<uint8_t>(static_cast<size_t>(w) * h * 3)};
  std::mt19937 rng(seed);
  for (auto& p : img.pixels) p = static_cast<uint8_t>(rng());
  return img;
}

Image8 gray_image(int w, int h, unsigned seed) {
  Image8 img{w, h, 1, std::vector<uint8_t>(static_cast<size_t>(w) * h)};
  std::mt19937 rng(seed);
  for (auto& p : img.pixels) p = rng() % 3 == 0 ? 255 : 0;
  return img;
}

Image16 depth_image(int w, int h, unsigned seed) {
  Image16 img{w, h, std::vector<uint16_t>(static_cast<size_t>(w) * h)};
  std::mt19937 rng(seed);
  for (auto& p : img.pixels) p = static_cast<uint16_t>(rng());
  img.pixels[0] = 0;
  img.pixels[1] = 255;
  img.pixels[2] = 256;
  img.pixels[3] = 65535;
  return img;
}

// Every error names a file; in text and JSON files also a line and column.
void expect_located(const Diagnostics& diags) {
  for (const Diagnostic& d : diags.items()) {
    if (d.severity != Severity::Error) continue;
    EXPECT_FALSE(d.file.empty()) << format_text(d);
    const std::string ext = fs::path(d.file).extension().string();
    if (ext == ".json" || ext == ".txt" || ext == ".csv") {
      EXPECT_GT(d.line, 0) << format_text(d);
      EXPECT_GT(d.col, 0) << format_text(d);
    }
  }
}

// The first error with `code` in `file` (nullptr if none).
const Diagnostic* find_error(const Diagnostics& diags, const std::string& code, const std::string& file) {
  for (const Diagnostic& d : diags.items())
    if (d.severity == Severity::Error && d.code == code && d.file == file) return &d;
  return nullptr;
}

std::string all_text(const Diagnostics& diags) {
  std::string out;
  for (const Diagnostic& d : diags.items()) out += format_text(d);
  return out;
}

// ---------------------------------------------------------------- PNG
TEST(SequencePng, RgbRoundTripAtEveryLevel) {
  TempDir dir;
  const Image8 img = rgb_image(17, 9, 1);
  for (int level : {0, 1, 3, 6, 9}) {
    std::string error;
    ASSERT_TRUE(write_png_rgb(dir / "a.png", img, &error, level)) << error;
    Image8 back;
    ASSERT_TRUE(read_png_rgb(dir / "a.png", &back, &error)) << error;
    EXPECT_EQ(back.width, 17);
    EXPECT_EQ(back.height, 9);
    EXPECT_EQ(back.channels, 3);
    EXPECT_EQ(back.pixels, img.pixels) << "level " << level;
  }
}

TEST(SequencePng, Gray8RoundTrip) {
  TempDir dir;
  const Image8 img = gray_image(31, 7, 2);
  std::string error;
  ASSERT_TRUE(write_png_gray8(dir / "m.png", img, &error)) << error;
  Image8 back;
  ASSERT_TRUE(read_png_gray8(dir / "m.png", &back, &error)) << error;
  EXPECT_EQ(back.channels, 1);
  EXPECT_EQ(back.pixels, img.pixels);
}

TEST(SequencePng, Gray16RoundTripKeepsFullRange) {
  TempDir dir;
  const Image16 img = depth_image(13, 11, 3);
  for (int level : {0, 2, 9}) {
    std::string error;
    ASSERT_TRUE(write_png_gray16(dir / "d.png", img, &error, level)) << error;
    Image16 back;
    ASSERT_TRUE(read_png_gray16(dir / "d.png", &back, &error)) << error;
    ASSERT_EQ(back.pixels.size(), img.pixels.size());
    EXPECT_EQ(back.pixels, img.pixels);
    EXPECT_EQ(back.pixels[2], 256);
    EXPECT_EQ(back.pixels[3], 65535);
  }
}

TEST(SequencePng, WrongKindIsNamedNotConverted) {
  TempDir dir;
  std::string error;
  ASSERT_TRUE(write_png_gray8(dir / "g.png", gray_image(4, 4, 1), &error));
  ASSERT_TRUE(write_png_rgb(dir / "c.png", rgb_image(4, 4, 1), &error));
  Image8 img;
  Image16 depth;
  EXPECT_FALSE(read_png_rgb(dir / "g.png", &img, &error));
  EXPECT_EQ(error, "is 8-bit grey, expected 8-bit RGB");
  EXPECT_FALSE(read_png_gray8(dir / "c.png", &img, &error));
  EXPECT_EQ(error, "is 8-bit RGB, expected 8-bit grey");
  EXPECT_FALSE(read_png_gray16(dir / "g.png", &depth, &error));
  EXPECT_EQ(error, "is 8-bit grey, expected 16-bit grey");
}

TEST(SequencePng, GarbageTruncatedAndMissingFilesAreErrors) {
  TempDir dir;
  std::string error;
  Image8 img;
  write_text(dir / "text.png", "this is not a png at all");
  EXPECT_FALSE(read_png_rgb(dir / "text.png", &img, &error));
  EXPECT_EQ(error, "is not a PNG file");
  write_text(dir / "empty.png", "");
  EXPECT_FALSE(read_png_rgb(dir / "empty.png", &img, &error));
  EXPECT_EQ(error, "is not a PNG file");
  EXPECT_FALSE(read_png_rgb(dir / "none.png", &img, &error));
  EXPECT_EQ(error, "does not exist");

  // A real PNG cut short, and one with a corrupted image chunk.
  ASSERT_TRUE(write_png_rgb(dir / "full.png", rgb_image(64, 64, 5), &error, 0));
  const std::string bytes = read_text(dir / "full.png");
  for (size_t cut : {size_t{12}, size_t{40}, bytes.size() / 2, bytes.size() - 5}) {
    write_text(dir / "cut.png", bytes.substr(0, cut));
    EXPECT_FALSE(read_png_rgb(dir / "cut.png", &img, &error)) << cut;
    EXPECT_EQ(error.rfind("is corrupt", 0), 0u) << error;
  }
  std::string flipped = bytes;
  for (size_t i = 100; i < flipped.size() - 20; i += 97) flipped[i] = static_cast<char>(flipped[i] ^ 0x5a);
  write_text(dir / "flipped.png", flipped);
  EXPECT_FALSE(read_png_rgb(dir / "flipped.png", &img, &error));
  EXPECT_EQ(error.rfind("is corrupt", 0), 0u) << error;
}

TEST(SequencePng, WriteRefusesInconsistentImages) {
  TempDir dir;
  std::string error;
  Image8 img = rgb_image(4, 4, 1);
  img.pixels.pop_back();
  EXPECT_FALSE(write_png_rgb(dir / "a.png", img, &error));
  EXPECT_FALSE(write_png_gray8(dir / "a.png", rgb_image(4, 4, 1), &error));
  EXPECT_FALSE(write_png_rgb(dir / "a.png", Image8{0, 0, 3, {}}, &error));
  EXPECT_FALSE(write_png_rgb(dir / "a.png", rgb_image(4, 4, 1), &error, 10));
  EXPECT_FALSE(write_png_rgb(dir / "no/such/folder/a.png", rgb_image(4, 4, 1), &error));
  EXPECT_FALSE(fs::exists(dir / "a.png"));
}

TEST(SequencePng, FrameFileNames) {
  EXPECT_EQ(frame_file(0), "000000.png");
  EXPECT_EQ(frame_file(123), "000123.png");
  EXPECT_EQ(frame_file(1234567), "1234567.png");
}

// ---------------------------------------------------------------- meta.json
Meta sample_meta(int frames, int w, int h) {
  Meta m;
  m.fps = 30;
  m.width = w;
  m.height = h;
  m.intrinsics = {525.5, 524.25, (w - 1) / 2.0, (h - 1) / 2.0};
  m.depth_scale = 0.001;
  m.frames = frames;
  m.gravity = {0, 0.1, -1};
  m.parts = {{"spout", "effector"}, {"handle", "receptor"}, {"body", "object"}};
  m.functions = {{"flow", "handle", "spout"}};
  m.source = "synthetic";
  m.extra["x-efc-seed"] = 42;
  m.extra["x-notes"] = {{"by", "test"}, {"values", {1, 2.5, "three"}}};
  return m;
}

// The example of shared/spec/sequence.md, copied into tests/data (shared/
// may be absent); tests/sequence_schema_test.py reads the same file.
std::string spec_example() {
  std::ifstream in(std::string(EFC_SOURCE_DIR) + "/tests/data/sequence-meta-example.json");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(SequenceMeta, ReadsTheSpecExample) {
  Diagnostics diags;
  Meta m;
  ASSERT_TRUE(read_meta_text(spec_example(), "meta.json", diags, &m)) << all_text(diags);
  EXPECT_EQ(m.width, 640);
  EXPECT_EQ(m.height, 480);
  EXPECT_EQ(m.frames, 300);
  EXPECT_DOUBLE_EQ(m.intrinsics.cx, 319.5);
  ASSERT_EQ(m.parts.size(), 2u);
  EXPECT_EQ(m.parts[0], (std::pair<std::string, std::string>{"handle", "receptor"}));
  ASSERT_EQ(m.functions.size(), 1u);
  EXPECT_EQ(m.functions[0].effector, "spout");
  EXPECT_EQ(m.source, "synthetic");
}

TEST(SequenceMeta, TextRoundTripKeepsOrderAndExtensions) {
  TempDir dir;
  const Meta m = sample_meta(5, 8, 6);
  const std::string text = meta_to_json_text(m);
  EXPECT_EQ(text.rfind("{\n  \"efc_sequence\": 1,\n  \"fps\": 30,", 0), 0u) << text;
  EXPECT_EQ(text.back(), '\n');
  std::string error;
  ASSERT_TRUE(write_meta(dir / "meta.json", m, &error)) << error;
  EXPECT_EQ(read_text(dir / "meta.json"), text);
  Diagnostics diags;
  Meta back;
  ASSERT_TRUE(read_meta(dir / "meta.json", diags, &back)) << all_text(diags);
  EXPECT_EQ(meta_to_json_text(back), text);
  EXPECT_EQ(back.parts, m.parts);  // file order, not sorted
  EXPECT_EQ(back.extra, m.extra);
  EXPECT_EQ(back.gravity, m.gravity);
  EXPECT_EQ(back.intrinsics.fy, 524.25);
}

TEST(SequenceMeta, WriteRefusesWhatCouldNotBeRead) {
  TempDir dir;
  std::string error;
  Meta m = sample_meta(5, 8, 6);
  m.fps = 0;
  EXPECT_FALSE(write_meta(dir / "meta.json", m, &error));
  EXPECT_NE(error.find("fps"), std::string::npos) << error;
  m = sample_meta(5, 8, 6);
  m.extra["notes"] = "no x- prefix";
  EXPECT_FALSE(write_meta(dir / "meta.json", m, &error));
  EXPECT_FALSE(fs::exists(dir / "meta.json"));
}

struct MetaCase {
  const char* text;
  const char* code;
  int line, col;
  const char* pointer;
  const char* message_part;
};

TEST(SequenceMeta, ProblemsAreLocated) {
  const MetaCase cases[] = {
      {"{\n  \"efc_sequence\": 1,\n  \"fps\": 30,,\n}\n", "E0003", 3, 13, "", ""},
      {"", "E0002", 1, 1, "", "empty"},
      {"[1, 2]\n", "E1002", 1, 1, "", "must be a JSON object"},
      {"{\"efc_sequence\": 1, \"fps\": 30, \"width\": \"640\", \"height\": 480,\n"
       " \"intrinsics\": {\"fx\": 1, \"fy\": 1, \"cx\": 0, \"cy\": 0}, \"frames\": 3}\n",
       "E1002", 1, 41, "/width", "'width' must be an integer, got a string"},
      {"{\"efc_sequence\": 1, \"fps\": 30, \"width\": 640.5, \"height\": 480,\n"
       " \"intrinsics\": {\"fx\": 1, \"fy\": 1, \"cx\": 0, \"cy\": 0}, \"frames\": 3}\n",
       "E1002", 1, 41, "/width", "must be an integer"},
      {"{\"efc_sequence\": 1, \"fps\": -30, \"width\": 640, \"height\": 480,\n"
       " \"intrinsics\": {\"fx\": 1, \"fy\": 1, \"cx\": 0, \"cy\": 0}, \"frames\": 3}\n",
       "E1002", 1, 28, "/fps", "'fps' must be > 0"},
      {"{\"efc_sequence\": 1, \"fps\": 30, \"width\": 640, \"height\": 480,\n"
       " \"intrinsics\": {\"fx\": 0, \"fy\": 1, \"cx\": 0, \"cy\": 0}, \"frames\": 3}\n",
       "E1002", 2, 23, "/intrinsics/fx", "'fx' must be > 0"},
      {"{\"efc_sequence\": 1, \"fps\": 30, \"width\": 640, \"height\": 480,\n"
       " \"intrinsics\": {\"fx\": 1, \"fy\": 1, \"cx\": 0, \"cy\": 0}}\n",
       "E1002", 1, 1, "/frames", "missing required key 'frames'"},
      {"{\"efc_sequence\": 2, \"fps\": 30, \"width\": 640, \"height\": 480,\n"
       " \"intrinsics\": {\"fx\": 1, \"fy\": 1, \"cx\": 0, \"cy\": 0}, \"frames\": 3}\n",
       "E1002", 1, 18, "/efc_sequence", "unsupported sequence format version 2"},
      {"{\"efc_sequence\": 1, \"fps\": 30, \"width\": 640, \"height\": 480, \"frames\": 3,\n"
       " \"intrinsics\": {\"fx\": 1, \"fy\": 1, \"cx\": 0, \"cy\": 0},\n"
       " \"framez\": 4}\n",
       "E1002", 3, 2, "/framez", "unknown key 'framez'"},
      {"{\"efc_sequence\": 1, \"fps\": 30, \"width\": 640, \"height\": 480, \"frames\": 3,\n"
       " \"intrinsics\": {\"fx\": 1, \"fy\": 1, \"cx\": 0, \"cy\": 0},\n"
       " \"parts\": {\"handle\": \"knob\"}}\n",
       "E1002", 3, 22, "/parts/handle", "unknown role 'knob'"},
      {"{\"efc_sequence\": 1, \"fps\": 30, \"width\": 640, \"height\": 480, \"frames\": 3,\n"
       " \"intrinsics\": {\"fx\": 1, \"fy\": 1, \"cx\": 0, \"cy\": 0},\n"
       " \"parts\": {\"handle\": \"receptor\", \"spout\": \"effector\"},\n"
       " \"functions\": [{\"name\": \"flow\", \"receptor\": \"handle\", \"effector\": \"tap\"}]}\n",
       "E1002", 4, 67, "/functions/0/effector", "'tap' is not listed in \"parts\""},
      {"{\"efc_sequence\": 1, \"fps\": 30, \"width\": 640, \"height\": 480, \"frames\": 3,\n"
       " \"intrinsics\": {\"fx\": 1, \"fy\": 1, \"cx\": 0, \"cy\": 0},\n"
       " \"gravity\": [0, 0, \"down\"]}\n",
       "E1002", 3, 20, "/gravity/2", "must be a number"},
  };
  for (const MetaCase& c : cases) {
    Diagnostics diags;
    Meta m;
    EXPECT_FALSE(read_meta_text(c.text, "SEQ/meta.json", diags, &m)) << c.text;
    ASSERT_TRUE(diags.has_errors()) << c.text;
    const Diagnostic& d = diags.items()[0];
    EXPECT_EQ(d.code, c.code) << c.text << all_text(diags);
    EXPECT_EQ(d.file, "SEQ/meta.json");
    EXPECT_EQ(d.line, c.line) << c.text << all_text(diags);
    EXPECT_EQ(d.col, c.col) << c.text << all_text(diags);
    EXPECT_EQ(d.pointer, c.pointer) << c.text << all_text(diags);
    EXPECT_NE(d.message.find(c.message_part), std::string::npos) << d.message;
  }
}

TEST(SequenceMeta, EveryProblemIsReportedInFileOrder) {
  const char* text =
      "{\"efc_sequence\": 1, \"fps\": \"fast\", \"width\": 0, \"height\": 480, \"frames\": 3,\n"
      " \"intrinsics\": {\"fx\": 1, \"fy\": 1, \"cx\": 0},\n"
      " \"x-mine\": {\"anything\": [1, 2]}, \"zzz\": true}\n";
  Diagnostics diags;
  Meta m;
  EXPECT_FALSE(read_meta_text(text, "meta.json", diags, &m));
  ASSERT_EQ(diags.error_count(), 4u) << all_text(diags);
  EXPECT_EQ(diags.items()[0].pointer, "/fps");
  EXPECT_EQ(diags.items()[1].pointer, "/width");
  EXPECT_EQ(diags.items()[2].pointer, "/intrinsics/cy");
  EXPECT_EQ(diags.items()[3].pointer, "/zzz");
  EXPECT_FALSE(diags.items()[0].source_line.empty());
  expect_located(diags);
}

TEST(SequenceMeta, MissingFileIsE1001) {
  Diagnostics diags;
  Meta m;
  EXPECT_FALSE(read_meta("/nonexistent/meta.json", diags, &m));
  ASSERT_EQ(diags.error_count(), 1u);
  EXPECT_EQ(diags.items()[0].code, "E1001");
  EXPECT_EQ(diags.items()[0].file, "/nonexistent/meta.json");
}

// ---------------------------------------------------------------- tracks
TEST(SequenceTracks, PosesAndHandsRoundTripExactly) {
  TempDir dir;
  std::vector<Pose> poses;
  std::vector<HandPoint> hands;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int i = 0; i < 10; ++i) {
    Pose p;
    p.t = i / 30.0;
    p.p = {u(rng), u(rng), u(rng)};
    std::array<double, 4> q{u(rng), u(rng), u(rng), u(rng)};
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (auto& c : q) c /= n;
    p.q = q;
    poses.push_back(p);
    HandPoint h;
    h.t = p.t;
    h.seen = i % 3 != 0;
    if (h.seen) h.p = {u(rng), u(rng), 1e-300 * u(rng)};
    hands.push_back(h);
  }
  std::string error;
  ASSERT_TRUE(write_poses(dir / "poses.txt", poses, &error)) << error;
  ASSERT_TRUE(write_hands(dir / "hands.txt", hands, &error)) << error;
  EXPECT_NE(read_text(dir / "hands.txt").find(" nan nan nan\n"), std::string::npos);
  Diagnostics diags;
  std::vector<Pose> poses2;
  std::vector<HandPoint> hands2;
  ASSERT_TRUE(read_poses(dir / "poses.txt", 10, diags, &poses2)) << all_text(diags);
  ASSERT_TRUE(read_hands(dir / "hands.txt", 10, diags, &hands2)) << all_text(diags);
  ASSERT_EQ(poses2.size(), poses.size());
  ASSERT_EQ(hands2.size(), hands.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(poses2[i].t, poses[i].t);
    EXPECT_EQ(poses2[i].p, poses[i].p);
    EXPECT_EQ(poses2[i].q, poses[i].q);
    EXPECT_EQ(hands2[i].t, hands[i].t);
    EXPECT_EQ(hands2[i].seen, hands[i].seen);
    if (hands[i].seen) {
      EXPECT_EQ(hands2[i].p, hands[i].p);
    }
  }
}

TEST(SequenceTracks, CommentsBlankLinesAndCrlfAreFine) {
  TempDir dir;
  write_text(dir / "poses.txt", "# header\r\n\r\n0 1 2 3 0 0 0 1\r\n  # indented comment\n0.5\t1 2 3 0 0 0.7071068 0.7071068\n");
  Diagnostics diags;
  std::vector<Pose> poses;
  ASSERT_TRUE(read_poses(dir / "poses.txt", 2, diags, &poses)) << all_text(diags);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[1].t, 0.5);
}

TEST(SequenceTracks, WriteRefusesNonFiniteValues) {
  TempDir dir;
  std::string error;
  Pose p;
  p.p[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(write_poses(dir / "poses.txt", {p}, &error));
  HandPoint h;
  h.seen = true;
  h.p[0] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(write_hands(dir / "hands.txt", {h}, &error));
}

struct TrackCase {
  const char* text;
  bool poses;
  const char* code;
  int line, col;
  const char* message_part;
};

TEST(SequenceTracks, BadLinesAreLocated) {
  const TrackCase cases[] = {
      {"# t tx ty tz qx qy qz qw\n0 0 0 0 0 0 0 1\n0.1 0 nan 0 0 0 0 1\n0.2 0 0 0 0 0 0 1\n", true, "E1006", 3, 7,
       "ty is nan"},
      {"0 0 0 0 0 0 0 1\n0.1 0 0 0 0 0 0 2\n0.2 0 0 0 0 0 0 1\n", true, "E1006", 2, 11, "length 2"},
      {"0 0 0 0 0 0 0 1\n0.1 0 0 0 0 0 1\n0.2 0 0 0 0 0 0 1\n", true, "E1006", 2, 16, "has 7"},
      {"0 0 0 0 0 0 0 1\n0.1 0 0 zero 0 0 0 1\n0.2 0 0 0 0 0 0 1\n", true, "E1006", 2, 9, "'zero' is not a number"},
      {"0 0 0 0 0 0 0 1\n0 0 0 0 0 0 0 1\n0.2 0 0 0 0 0 0 1\n", true, "E1006", 2, 1, "not after"},
      {"0 0 0 0 0 0 0 1\n0.1 0 0 0 0 0 0 1\n", true, "E1007", 2, 1, "has 2 pose lines, meta.json says 3"},
      {"0 0 0 0 0 0 0 1\n0.1 0 0 0 0 0 0 1\n0.2 0 0 0 0 0 0 1\n0.3 0 0 0 0 0 0 1\n", true, "E1007", 4, 1,
       "has 4 pose lines"},
      {"", true, "E1007", 1, 1, "has 0 pose lines"},
      {"0 1 2 3\n0.1 nan 2 nan\n0.2 nan nan nan\n", false, "E1006", 2, 5, "only some of x y z are nan"},
      {"0 1 2 3\n0.1 1 2 3 4\n0.2 nan nan nan\n", false, "E1006", 2, 11, "has 5"},
      {"0 1 2 3\nnan nan nan nan\n0.2 nan nan nan\n", false, "E1006", 2, 1, "time is nan"},
  };
  for (const TrackCase& c : cases) {
    TempDir dir;
    const std::string path = dir / (c.poses ? "poses.txt" : "hands.txt");
    write_text(path, c.text);
    Diagnostics diags;
    std::vector<Pose> poses;
    std::vector<HandPoint> hands;
    const bool ok = c.poses ? read_poses(path, 3, diags, &poses) : read_hands(path, 3, diags, &hands);
    EXPECT_FALSE(ok) << c.text;
    ASSERT_TRUE(diags.has_errors()) << c.text;
    const Diagnostic& d = diags.items()[0];
    EXPECT_EQ(d.code, c.code) << c.text << all_text(diags);
    EXPECT_EQ(d.file, path);
    EXPECT_EQ(d.line, c.line) << c.text << all_text(diags);
    EXPECT_EQ(d.col, c.col) << c.text << all_text(diags);
    EXPECT_NE(d.message.find(c.message_part), std::string::npos) << d.message;
    expect_located(diags);
  }
}

// ---------------------------------------------------------------- a whole folder
constexpr int kFrames = 3, kW = 8, kH = 6;

// A complete small sequence: every optional part present.
void write_sequence(const std::string& dir) {
  std::string error;
  fs::create_directories(dir);
  ASSERT_TRUE(write_meta((fs::path(dir) / "meta.json").string(), sample_meta(kFrames, kW, kH), &error)) << error;
  for (const char* sub : {"rgb", "depth", "masks/handle", "masks/hand", "truth"})
    fs::create_directories(fs::path(dir) / sub);
  std::vector<Pose> poses;
  std::vector<HandPoint> hands;
  for (int f = 0; f < kFrames; ++f) {
    const std::string name = frame_file(f);
    ASSERT_TRUE(write_png_rgb(dir + "/rgb/" + name, rgb_image(kW, kH, f), &error, 2)) << error;
    ASSERT_TRUE(write_png_gray16(dir + "/depth/" + name, depth_image(kW, kH, f), &error, 2)) << error;
    ASSERT_TRUE(write_png_gray8(dir + "/masks/handle/" + name, gray_image(kW, kH, f), &error, 2)) << error;
    ASSERT_TRUE(write_png_gray8(dir + "/masks/hand/" + name, gray_image(kW, kH, f + 9), &error, 2)) << error;
    Pose p;
    p.t = f / 30.0;
    p.p = {0.1 * f, -0.2, 1.5};
    poses.push_back(p);
    HandPoint h;
    h.t = p.t;
    h.seen = f != 1;
    h.p = {0.01 * f, 0.02, 0.03};
    hands.push_back(h);
  }
  ASSERT_TRUE(write_poses(dir + "/poses.txt", poses, &error)) << error;
  ASSERT_TRUE(write_hands(dir + "/hands.txt", hands, &error)) << error;
  write_text(dir + "/truth/spec.json", "{\"efc\": 1, \"name\": \"tap\", \"parts\": []}\n");
  write_text(dir + "/truth/object_pose.json",
             "{\"object_to_world\": [1, 0, 0, 0.5, 0, 1, 0, 0, 0, 0, 1, 0.8, 0, 0, 0, 1]}\n");
  write_text(dir + "/truth/joints.csv", "t,handle\n0,0\n0.0333,0.1\n0.0667,0.2\n");
  write_text(dir + "/truth/effects.csv", "t,flow.s_E\n0,0\n0.0333,0\n0.0667,1\n");
}

TEST(SequenceFolder, WrittenFolderReadsBackUnchanged) {
  TempDir tmp;
  const std::string dir = tmp / "SEQ";
  write_sequence(dir);
  Diagnostics diags;
  Sequence s;
  ASSERT_TRUE(s.open(dir, diags)) << all_text(diags);
  EXPECT_TRUE(s.check_all(diags)) << all_text(diags);
  EXPECT_TRUE(diags.items().empty()) << all_text(diags);
  EXPECT_EQ(s.dir(), dir);
  EXPECT_TRUE(s.has_depth());
  EXPECT_TRUE(s.has_poses());
  EXPECT_TRUE(s.has_hands());
  EXPECT_TRUE(s.has_truth());
  EXPECT_EQ(s.mask_names(), (std::vector<std::string>{"hand", "handle"}));
  EXPECT_EQ(meta_to_json_text(s.meta()), read_text(dir + "/meta.json"));
  EXPECT_EQ(s.rgb_path(2), dir + "/rgb/000002.png");
  for (int f = 0; f < kFrames; ++f) {
    Image8 rgb, mask;
    Image16 depth;
    ASSERT_TRUE(s.read_rgb(f, diags, &rgb));
    ASSERT_TRUE(s.read_depth(f, diags, &depth));
    ASSERT_TRUE(s.read_mask("handle", f, diags, &mask));
    EXPECT_EQ(rgb.pixels, rgb_image(kW, kH, f).pixels);
    EXPECT_EQ(depth.pixels, depth_image(kW, kH, f).pixels);
    EXPECT_EQ(mask.pixels, gray_image(kW, kH, f).pixels);
  }
  std::vector<Pose> poses;
  std::vector<HandPoint> hands;
  ASSERT_TRUE(s.read_poses(diags, &poses));
  ASSERT_TRUE(s.read_hands(diags, &hands));
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_EQ(poses[2].t, 2 / 30.0);
  EXPECT_EQ(poses[1].p[0], 0.1);
  EXPECT_FALSE(hands[1].seen);
  EXPECT_TRUE(hands[2].seen);
  EXPECT_EQ(hands[2].p[0], 0.02);
  Image8 rgb;
  EXPECT_FALSE(s.read_rgb(3, diags, &rgb));  // past the end: an error, not a crash
  EXPECT_EQ(diags.items().back().code, "E1003");
}

TEST(SequenceFolder, OnlyRgbAndMetaIsValid) {
  TempDir tmp;
  const std::string dir = tmp / "SEQ";
  Meta m = sample_meta(2, 4, 4);
  m.parts.clear();
  m.functions.clear();
  m.extra = nlohmann::json::object();
  fs::create_directories(dir + "/rgb");
  std::string error;
  ASSERT_TRUE(write_meta(dir + "/meta.json", m, &error));
  for (int f = 0; f < 2; ++f) ASSERT_TRUE(write_png_rgb(dir + "/rgb/" + frame_file(f), rgb_image(4, 4, f), &error));
  Diagnostics diags;
  Sequence s;
  ASSERT_TRUE(s.open(dir, diags));
  EXPECT_TRUE(s.check_all(diags)) << all_text(diags);
  EXPECT_FALSE(s.has_depth() || s.has_poses() || s.has_hands() || s.has_truth());
  EXPECT_TRUE(s.mask_names().empty());
}

TEST(SequenceFolder, NotASequenceIsE1001) {
  TempDir tmp;
  struct Case {
    std::string dir, file;
  };
  fs::create_directories(tmp / "empty");
  fs::create_directories(tmp / "nometa/rgb");
  write_text(tmp / "afile", "x");
  const Case cases[] = {{tmp / "empty", tmp / "empty"},
                        {tmp / "nometa", tmp / "nometa/meta.json"},
                        {tmp / "missing", tmp / "missing"},
                        {tmp / "afile", tmp / "afile"}};
  for (const Case& c : cases) {
    Diagnostics diags;
    Sequence s;
    EXPECT_FALSE(s.open(c.dir, diags)) << c.dir;
    ASSERT_EQ(diags.error_count(), 1u) << all_text(diags);
    EXPECT_EQ(diags.items()[0].code, "E1001");
    EXPECT_EQ(diags.items()[0].file, c.file);
  }
}

TEST(SequenceFolder, BadMetaIsLocatedInTheFolder) {
  TempDir tmp;
  const std::string dir = tmp / "SEQ";
  write_sequence(dir);
  write_text(dir + "/meta.json", "{\n  \"efc_sequence\": 1\n  \"fps\": 30\n}\n");
  Diagnostics diags;
  Sequence s;
  EXPECT_FALSE(s.open(dir, diags));
  ASSERT_TRUE(diags.has_errors());
  EXPECT_EQ(diags.items()[0].file, dir + "/meta.json");
  EXPECT_EQ(diags.items()[0].code, "E0003");
  EXPECT_EQ(diags.items()[0].line, 3);
  expect_located(diags);
}

// Breaks a good folder with `damage`, then expects check_all to report
// `code` in `file` (relative to the folder).
void expect_problem(const std::function<void(const std::string&)>& damage, const std::string& code,
                    const std::string& file, int line = 0, int col = 0) {
  TempDir tmp;
  const std::string dir = tmp / "SEQ";
  write_sequence(dir);
  damage(dir);
  Diagnostics diags;
  Sequence s;
  ASSERT_TRUE(s.open(dir, diags)) << all_text(diags);
  EXPECT_FALSE(s.check_all(diags)) << code << " " << file;
  const Diagnostic* d = find_error(diags, code, dir + "/" + file);
  ASSERT_NE(d, nullptr) << "no " << code << " in " << file << ":\n" << all_text(diags);
  if (line) {
    EXPECT_EQ(d->line, line) << format_text(*d);
  }
  if (col) {
    EXPECT_EQ(d->col, col) << format_text(*d);
  }
  expect_located(diags);
}

TEST(SequenceFolder, EveryKindOfDamageIsLocated) {
  std::string error;
  // A missing frame, named.
  expect_problem([](const std::string& d) { fs::remove(d + "/rgb/000002.png"); }, "E1003", "rgb/000002.png");
  expect_problem([](const std::string& d) { fs::remove_all(d + "/rgb"); }, "E1003", "rgb");
  expect_problem([](const std::string& d) { fs::remove(d + "/masks/hand/000000.png"); }, "E1003",
                 "masks/hand/000000.png");
  // Wrong size, wrong kind, garbage.
  expect_problem(
      [&](const std::string& d) { write_png_gray16(d + "/depth/000001.png", depth_image(kW + 1, kH, 1), &error); },
      "E1004", "depth/000001.png");
  expect_problem(
      [&](const std::string& d) { write_png_rgb(d + "/masks/handle/000001.png", rgb_image(kW, kH, 1), &error); },
      "E1005", "masks/handle/000001.png");
  expect_problem([](const std::string& d) { write_text(d + "/rgb/000000.png", "GIF89a garbage"); }, "E1005",
                 "rgb/000000.png");
  expect_problem(
      [](const std::string& d) {
        const std::string bytes = read_text(d + "/depth/000002.png");
        write_text(d + "/depth/000002.png", bytes.substr(0, bytes.size() / 2));
      },
      "E1005", "depth/000002.png");
  // Frames beyond "frames".
  expect_problem(
      [&](const std::string& d) { write_png_rgb(d + "/rgb/000003.png", rgb_image(kW, kH, 3), &error); }, "E1007",
      "rgb/000003.png");
  expect_problem(
      [&](const std::string& d) { write_png_gray8(d + "/masks/hand/000007.png", gray_image(kW, kH, 3), &error); },
      "E1007", "masks/hand/000007.png");
  // Tracks.
  expect_problem([](const std::string& d) { write_text(d + "/poses.txt", "0 0 0 0 0 0 0 1\n0.1 nan 0 0 0 0 0 1\n0.2 0 0 0 0 0 0 1\n"); },
                 "E1006", "poses.txt", 2, 5);
  expect_problem([](const std::string& d) { write_text(d + "/poses.txt", "# two\n0 0 0 0 0 0 0 1\n0.1 0 0 0 0 0 0 1\n"); },
                 "E1007", "poses.txt", 3, 1);
  expect_problem([](const std::string& d) { write_text(d + "/poses.txt", "0 0 0 0 0 0 0 1\n0.1 0 0 0 1 1 0 0\n0.2 0 0 0 0 0 0 1\n"); },
                 "E1006", "poses.txt", 2, 11);
  expect_problem([](const std::string& d) { write_text(d + "/hands.txt", "0 1 2 3\n0.1 1 nan 3\n0.2 nan nan nan\n"); },
                 "E1006", "hands.txt", 2, 7);
  // Masks named after nothing listed.
  expect_problem([](const std::string& d) { fs::create_directories(d + "/masks/handel"); }, "E1009", "masks/handel");
  // truth/.
  expect_problem([](const std::string& d) { write_text(d + "/truth/spec.json", "{\"efc\": 1,\n]"); }, "E0003",
                 "truth/spec.json", 2, 1);
  expect_problem([](const std::string& d) { write_text(d + "/truth/object_pose.json", "{\"object_to_world\": [1, 2, 3]}"); },
                 "E1008", "truth/object_pose.json", 1, 21);
  expect_problem([](const std::string& d) { write_text(d + "/truth/joints.csv", "time,handle\n0,0\n0.1,0\n0.2,0\n"); },
                 "E1008", "truth/joints.csv", 1, 1);
  expect_problem([](const std::string& d) { write_text(d + "/truth/joints.csv", "t,handle\n0,0\n0.1,x\n0.2,0\n"); },
                 "E1008", "truth/joints.csv", 3, 5);
  expect_problem([](const std::string& d) { write_text(d + "/truth/effects.csv", "t,flow.s_E\n0,0\n0.1,0\n"); },
                 "E1007", "truth/effects.csv", 3, 1);
}

TEST(SequenceFolder, ManyBadFramesAreListedThenCounted) {
  TempDir tmp;
  const std::string dir = tmp / "SEQ";
  fs::create_directories(dir + "/rgb");
  std::string error;
  Meta m = sample_meta(30, 4, 4);
  ASSERT_TRUE(write_meta(dir + "/meta.json", m, &error));
  for (int f = 0; f < 30; ++f) ASSERT_TRUE(write_png_rgb(dir + "/rgb/" + frame_file(f), rgb_image(5, 4, f), &error));
  Diagnostics diags;
  Sequence s;
  ASSERT_TRUE(s.open(dir, diags));
  EXPECT_FALSE(s.check_all(diags));
  EXPECT_EQ(diags.error_count(), 20u);
  ASSERT_EQ(diags.items().size(), 21u);
  EXPECT_EQ(diags.items().back().severity, Severity::Note);
  EXPECT_EQ(diags.items().back().file, dir + "/rgb");
  EXPECT_NE(diags.items().back().message.find("10 more"), std::string::npos);
}

TEST(SequenceFolder, HugeFrameCountOverFewFilesIsQuick) {
  TempDir tmp;
  const std::string dir = tmp / "SEQ";
  fs::create_directories(dir + "/rgb");
  std::string error;
  Meta m = sample_meta(2000000000, 4, 4);
  ASSERT_TRUE(write_meta(dir + "/meta.json", m, &error));
  for (int f = 0; f < 2; ++f) ASSERT_TRUE(write_png_rgb(dir + "/rgb/" + frame_file(f), rgb_image(4, 4, f), &error));
  ASSERT_TRUE(write_png_rgb(dir + "/rgb/" + frame_file(30), rgb_image(5, 4, 0), &error));
  Diagnostics diags;
  Sequence s;
  ASSERT_TRUE(s.open(dir, diags));
  EXPECT_FALSE(s.check_all(diags));
  EXPECT_EQ(diags.error_count(), 20u);
  EXPECT_EQ(diags.items()[0].file, dir + "/rgb/000002.png");
  // 2..21 listed; of the rest, frame 30 is there (and of the wrong size).
  EXPECT_NE(diags.items().back().message.find(std::to_string(2000000000 - 22 - 1 + 1) + " more"), std::string::npos)
      << diags.items().back().message;
}

// tests/codes_catalogue_test.cc does not scan sequence/: the same check here.
TEST(SequenceCodes, EveryEmittedCodeIsExplained) {
  const std::regex code_literal("\"([EW][0-9]{4})\"");
  int seen = 0;
  for (const auto& e : fs::directory_iterator(fs::path(EFC_SOURCE_DIR) / "sequence")) {
    if (e.path().extension() != ".cc") continue;
    const std::string text = read_text(e.path().string());
    for (std::sregex_iterator it(text.begin(), text.end(), code_literal), end; it != end; ++it) {
      EXPECT_NE(find_code((*it)[1]), nullptr) << (*it)[1] << " used in " << e.path();
      ++seen;
    }
  }
  EXPECT_GE(seen, 9);
}

}  // namespace
}  // namespace efc::seq
