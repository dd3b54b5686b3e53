// The blob signals of the template stage (frame_signals.cc) on a small
// recording drawn here pixel by pixel, where what each pixel is is known:
// a vent and a lamp side by side above a low body, a grey wall behind.
//   frame 0: a thin bright streak (an air mote) just above the vent, inside
//            the lamp's search space too: it counts for the vent alone.
//   frame 1: no mote, but a lit white patch of the wall whose edge is a
//            shadow's ragged teeth: it counts for neither.
//   frame 2: the wall alone: nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "compiler/diagnostics.h"
#include "pipeline/templates/frame_signals.h"
#include "pipeline/templates/template_input.h"
#include "sequence/sequence.h"

namespace fs = std::filesystem;
using efc::pipeline::EffectorSignals;

namespace {

constexpr int kW = 160, kH = 120, kFrames = 3;
constexpr double kF = 200, kCx = 79.5, kCy = 59.5;
constexpr double kWall = 3.0;  // m, along the optical axis

// The object's frame: x right, y away from the camera, z up; its origin 2 m
// ahead of the camera and 0.3 m below its axis. The camera sits at the world
// origin (OpenCV axes), so the world is the camera's frame.
Eigen::Isometry3d object_to_world() {
  Eigen::Matrix3d R;
  R.col(0) = Eigen::Vector3d(1, 0, 0);
  R.col(1) = Eigen::Vector3d(0, 0, 1);
  R.col(2) = Eigen::Vector3d(0, -1, 0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = Eigen::Vector3d(0, 0.3, 2.0);
  return T;
}

struct Box {
  const char* name;
  const char* role;
  Eigen::Vector3d lo, hi;  // object frame
};
const Box kBoxes[] = {
    {"body", "object", {-0.4, -0.1, 0.0}, {0.4, 0.1, 0.1}},
    {"vent", "effector", {-0.1, -0.01, 0.34}, {0.0, 0.01, 0.36}},
    {"lamp", "effector", {0.235, -0.015, 0.335}, {0.265, 0.015, 0.365}},
    {"knob", "receptor", {0.3, -0.11, 0.05}, {0.34, -0.1, 0.09}},
};

// The pixel rectangle a box covers (its corners projected).
void project(const Box& b, int* u0, int* v0, int* u1, int* v1) {
  double a0 = 1e9, b0 = 1e9, a1 = -1e9, b1 = -1e9;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d p(c & 1 ? b.hi.x() : b.lo.x(), c & 2 ? b.hi.y() : b.lo.y(), c & 4 ? b.hi.z() : b.lo.z());
    const Eigen::Vector3d w = object_to_world() * p;
    const double u = kF * w.x() / w.z() + kCx, v = kF * w.y() / w.z() + kCy;
    a0 = std::min(a0, u), a1 = std::max(a1, u), b0 = std::min(b0, v), b1 = std::max(b1, v);
  }
  *u0 = static_cast<int>(std::floor(a0)), *u1 = static_cast<int>(std::ceil(a1));
  *v0 = static_cast<int>(std::floor(b0)), *v1 = static_cast<int>(std::ceil(b1));
}

// The pixel where an object-frame point is seen.
void pixel_of(const Eigen::Vector3d& p, int* u, int* v) {
  const Eigen::Vector3d w = object_to_world() * p;
  *u = static_cast<int>(std::lround(kF * w.x() / w.z() + kCx));
  *v = static_cast<int>(std::lround(kF * w.y() / w.z() + kCy));
}

struct Recording {
  fs::path dir;
  efc::seq::Sequence sequence;
  efc::pipeline::TemplateInput input;
  int vent = -1, lamp = -1;

  Recording() {
    dir = fs::temp_directory_path() / ("efc_blobs_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    for (const char* sub : {"rgb", "depth"}) fs::create_directories(dir / sub);
    for (const Box& b : kBoxes) fs::create_directories(dir / "masks" / b.name);
    efc::seq::Meta meta;
    meta.width = kW, meta.height = kH, meta.frames = kFrames;
    meta.intrinsics = {kF, kF, kCx, kCy};
    for (const Box& b : kBoxes) meta.parts.push_back({b.name, b.role});
    meta.functions = {{"blow", "knob", "vent"}, {"light", "knob", "lamp"}};
    std::string error;
    EXPECT_TRUE(efc::seq::write_meta((dir / "meta.json").string(), meta, &error)) << error;
    for (int f = 0; f < kFrames; ++f) draw(f);
    efc::Diagnostics diags;
    EXPECT_TRUE(sequence.open(dir.string(), diags));
    input.sequence = &sequence;
    input.camera_to_world.assign(kFrames, Eigen::Isometry3d::Identity());
    input.object_to_world = object_to_world();
    for (const Box& b : kBoxes) {
      efc::pipeline::PartObservation o;
      o.name = b.name;
      o.role = b.role;
      o.joint_type = "fixed";
      o.motion.assign(kFrames, Eigen::Isometry3d::Identity());
      o.bounds = Eigen::AlignedBox3d(b.lo, b.hi);
      if (o.name == "vent") vent = static_cast<int>(input.parts.size());
      if (o.name == "lamp") lamp = static_cast<int>(input.parts.size());
      input.parts.push_back(o);
    }
    input.functions = meta.functions;
  }
  ~Recording() { fs::remove_all(dir); }

  void draw(int f) {
    efc::seq::Image8 rgb;
    rgb.width = kW, rgb.height = kH, rgb.channels = 3;
    rgb.pixels.assign(static_cast<size_t>(kW) * kH * 3, 60);
    efc::seq::Image16 depth;
    depth.width = kW, depth.height = kH;
    depth.pixels.assign(static_cast<size_t>(kW) * kH, static_cast<uint16_t>(kWall * 1000));
    auto put = [&](int u, int v, int r, int g, int b) {
      if (u < 0 || v < 0 || u >= kW || v >= kH) return;
      uint8_t* p = &rgb.pixels[3 * (static_cast<size_t>(v) * kW + u)];
      p[0] = static_cast<uint8_t>(r), p[1] = static_cast<uint8_t>(g), p[2] = static_cast<uint8_t>(b);
    };
    if (f == 0) {
      // A mote's streak, 2 px wide and 8 px tall, 9 cm above the vent's
      // right end, where the lamp's space (0.3 m around it) reaches too.
      int u, v;
      pixel_of(Eigen::Vector3d(0.0, 0.0, 0.45), &u, &v);
      for (int dv = -4; dv < 4; ++dv)
        for (int du = 0; du < 2; ++du) put(u + du, v + dv, 230, 235, 245);
    } else if (f == 1) {
      // A lit patch of the wall below the vent (the space droplets fall
      // through), its upper edge in ragged teeth 1 px wide, 3 px apart,
      // reaching 4 px into the shadow above it.
      int u0, v0, u1, v1;
      pixel_of(Eigen::Vector3d(-0.2, 0.0, 0.28), &u0, &v0);
      pixel_of(Eigen::Vector3d(0.1, 0.0, 0.15), &u1, &v1);
      for (int v = v0; v <= v1; ++v)
        for (int u = u0; u <= u1; ++u) put(u, v, 100, 100, 100);  // the shadow
      const int edge = (v0 + v1) / 2;
      for (int v = edge; v <= v1; ++v)
        for (int u = u0; u <= u1; ++u) put(u, v, 255, 255, 253);  // lit
      for (int u = u0 + 1; u <= u1 - 1; u += 3)
        for (int v = edge - 4; v < edge; ++v) put(u, v, 255, 255, 253);  // teeth
    }
    // The parts over it all, each its own colour, depth and mask.
    std::vector<efc::seq::Image8> masks;
    for (const Box& b : kBoxes) {
      efc::seq::Image8 m;
      m.width = kW, m.height = kH, m.channels = 1;
      m.pixels.assign(static_cast<size_t>(kW) * kH, 0);
      int u0, v0, u1, v1;
      project(b, &u0, &v0, &u1, &v1);
      const double z = (object_to_world() * (0.5 * (b.lo + b.hi))).z();
      for (int v = std::max(0, v0); v <= std::min(kH - 1, v1); ++v)
        for (int u = std::max(0, u0); u <= std::min(kW - 1, u1); ++u) {
          m.pixels[static_cast<size_t>(v) * kW + u] = 255;
          put(u, v, 140, 120, 90);
          depth.pixels[static_cast<size_t>(v) * kW + u] = static_cast<uint16_t>(z * 1000);
        }
      masks.push_back(m);
    }
    std::string error;
    const std::string name = efc::seq::frame_file(f);
    EXPECT_TRUE(efc::seq::write_png_rgb((dir / "rgb" / name).string(), rgb, &error)) << error;
    EXPECT_TRUE(efc::seq::write_png_gray16((dir / "depth" / name).string(), depth, &error)) << error;
    for (size_t i = 0; i < masks.size(); ++i)
      EXPECT_TRUE(efc::seq::write_png_gray8((dir / "masks" / kBoxes[i].name / name).string(), masks[i], &error))
          << error;
  }
};

}  // namespace

TEST(TemplatesBlobs, AMoteCountsForTheNearestEffectorAndAShadowsTeethForNone) {
  Recording rec;
  ASSERT_GE(rec.vent, 0);
  ASSERT_GE(rec.lamp, 0);
  int failed = 0;
  const std::vector<EffectorSignals> sig = efc::pipeline::measure_effectors(rec.input, {rec.vent, rec.lamp}, 1, &failed);
  EXPECT_EQ(failed, 0);
  ASSERT_EQ(sig.size(), 2u);
  const EffectorSignals &vent = sig[0], &lamp = sig[1];
  ASSERT_EQ(vent.motes.size(), static_cast<size_t>(kFrames));
  ASSERT_EQ(lamp.motes.size(), static_cast<size_t>(kFrames));
  for (int f = 0; f < kFrames; ++f) {
    // Both effectors' spaces are in view in every frame: observed, not NaN.
    ASSERT_TRUE(std::isfinite(vent.motes[f])) << f;
    ASSERT_TRUE(std::isfinite(lamp.motes[f])) << f;
  }
  // Frame 0: the streak is the vent's (its ray passes 9 cm from the vent,
  // 25 cm from the lamp), and each of its pixels counts once.
  EXPECT_GT(vent.motes[0], 0);
  EXPECT_EQ(lamp.motes[0], 0);
  EXPECT_GT(vent.mote_points, 0);
  EXPECT_EQ(lamp.mote_points, 0);
  // Frame 1: the lit teeth are blobs to the row-and-column test, but they
  // belong to the lit patch beside them: not motes.
  EXPECT_EQ(vent.motes[1], 0);
  EXPECT_EQ(lamp.motes[1], 0);
  // Frame 2: nothing at all.
  EXPECT_EQ(vent.motes[2], 0);
  EXPECT_EQ(lamp.motes[2], 0);
  // No droplets anywhere (nothing water-blue).
  for (int f = 0; f < kFrames; ++f) EXPECT_EQ(vent.droplets[f] + lamp.droplets[f], 0) << f;
}

// Measured alone, the lamp takes the streak (no nearer effector claims it):
// the attribution is between the effectors measured together.
TEST(TemplatesBlobs, AnEffectorMeasuredAloneKeepsWhatItsSpaceSees) {
  Recording rec;
  int failed = 0;
  const std::vector<EffectorSignals> sig = efc::pipeline::measure_effectors(rec.input, {rec.lamp}, 1, &failed);
  ASSERT_EQ(sig.size(), 1u);
  EXPECT_GT(sig[0].motes[0], 0);
  EXPECT_EQ(sig[0].motes[1], 0);
}
