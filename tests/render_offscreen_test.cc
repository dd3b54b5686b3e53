// Offscreen rendering (OSMesa, no GPU, no display) of small MJCF models.
#include "harness/render.h"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

std::string g_warnings;

void test_error_handler(const char* msg) { throw std::runtime_error(msg ? msg : "mujoco error"); }
void test_warning_handler(const char* msg) { g_warnings += msg ? msg : ""; g_warnings += "\n"; }

// MuJoCo's default error handler waits for Enter; never let the test hang.
struct InstallHandlers {
  InstallHandlers() {
    mju_user_error = test_error_handler;
    mju_user_warning = test_warning_handler;
  }
} install_handlers;

std::string scene_xml(double light_diffuse, bool with_camera, const std::string& extra_visual = "") {
  char light[64];
  std::snprintf(light, sizeof light, "%g %g %g", light_diffuse, light_diffuse, light_diffuse);
  std::string xml = R"(<mujoco model="render_test">
  <visual>
    <headlight ambient="0 0 0" diffuse="0 0 0" specular="0 0 0"/>
    )" + extra_visual + R"(
  </visual>
  <worldbody>
    <light name="lamp" pos="0 -1.5 1" dir="0 1 -0.4" directional="true" diffuse=")" +
                    std::string(light) + R"(" specular="0 0 0" ambient="0 0 0"/>
)";
  if (with_camera)
    xml += R"(    <camera name="efc_camera" pos="0 -1.2 0.2" xyaxes="1 0 0 0 0.17 1"/>
)";
  xml += R"(    <body name="thing" pos="0 0 0">
      <geom name="box" type="box" size="0.2 0.2 0.2" rgba="0.9 0.3 0.1 1"/>
    </body>
  </worldbody>
</mujoco>
)";
  return xml;
}

mjModel* load_xml(const std::string& xml, const std::string& name) {
  std::string path = testing::TempDir() + "efc_render_" + name + ".xml";
  {
    std::ofstream f(path);
    f << xml;
  }
  char err[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, err, sizeof err);
  std::remove(path.c_str());
  EXPECT_NE(m, nullptr) << err;
  return m;
}

struct Stats {
  double mean = 0, variance = 0;
};

Stats stats(const std::vector<unsigned char>& rgb) {
  Stats s;
  if (rgb.empty()) return s;
  double sum = 0, sum2 = 0;
  for (unsigned char c : rgb) {
    sum += c;
    sum2 += double(c) * c;
  }
  s.mean = sum / rgb.size();
  s.variance = sum2 / rgb.size() - s.mean * s.mean;
  return s;
}

std::vector<int> pixel(const std::vector<unsigned char>& rgb, int w, int x, int y) {
  size_t i = (static_cast<size_t>(y) * w + x) * 3;
  return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

// Renders a model in its initial state; returns false (with a test failure) on error.
bool render(mjModel* m, int w_req, int h_req, std::vector<unsigned char>* rgb, int* w, int* h) {
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  efc::OffscreenRenderer r(m, w_req, h_req);
  EXPECT_TRUE(r.ok()) << r.error();
  bool ok = r.ok() && r.render_rgb(m, d, rgb, w, h);
  EXPECT_TRUE(ok) << r.error();
  mj_deleteData(d);
  return ok;
}

uint32_t be32(const unsigned char* p) {
  return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | p[3];
}

TEST(RenderOffscreen, BoxIsVisibleThroughEfcCamera) {
  mjModel* m = load_xml(scene_xml(0.8, true), "box");
  ASSERT_NE(m, nullptr);
  std::vector<unsigned char> rgb;
  int w = 0, h = 0;
  ASSERT_TRUE(render(m, 160, 120, &rgb, &w, &h));
  EXPECT_EQ(w, 160);
  EXPECT_EQ(h, 120);
  ASSERT_EQ(rgb.size(), size_t(w) * h * 3);
  Stats s = stats(rgb);
  EXPECT_GT(s.variance, 0.0);
  std::vector<int> centre = pixel(rgb, w, w / 2, h / 2);
  // The box is orange-ish: red channel dominates in the centre.
  EXPECT_GT(centre[0], 40);
  EXPECT_GT(centre[0], centre[2]);
  for (auto xy : {std::pair<int, int>{0, 0}, {w - 1, 0}, {0, h - 1}, {w - 1, h - 1}}) {
    EXPECT_NE(pixel(rgb, w, xy.first, xy.second), centre)
        << "corner " << xy.first << "," << xy.second;
  }
  mj_deleteModel(m);
}

TEST(RenderOffscreen, FreeCameraFramesModelWithoutEfcCamera) {
  mjModel* m = load_xml(scene_xml(0.8, false), "free");
  ASSERT_NE(m, nullptr);
  std::vector<unsigned char> rgb;
  int w = 0, h = 0;
  ASSERT_TRUE(render(m, 200, 150, &rgb, &w, &h));
  EXPECT_GT(stats(rgb).variance, 0.0);
  std::vector<int> centre = pixel(rgb, w, w / 2, h / 2);
  EXPECT_NE(pixel(rgb, w, 0, 0), centre);
  mj_deleteModel(m);
}

TEST(RenderOffscreen, WritesPngWithRightSizeAndSignature) {
  mjModel* m = load_xml(scene_xml(0.8, true), "png");
  ASSERT_NE(m, nullptr);
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  std::string path = testing::TempDir() + "efc_render_test.png";
  std::remove(path.c_str());
  {
    efc::OffscreenRenderer r(m, 320, 240);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r.render_png(m, d, path)) << r.error();
    // Rendering twice with one renderer works (the harness writes many frames).
    ASSERT_TRUE(r.render_png(m, d, path)) << r.error();
  }
  std::ifstream f(path, std::ios::binary);
  ASSERT_TRUE(f.good());
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(f)),
                                   std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 33u);
  const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  EXPECT_TRUE(std::equal(sig, sig + 8, bytes.begin()));
  EXPECT_EQ(std::string(bytes.begin() + 12, bytes.begin() + 16), "IHDR");
  EXPECT_EQ(be32(&bytes[16]), 320u);
  EXPECT_EQ(be32(&bytes[20]), 240u);
  EXPECT_EQ(bytes[24], 8);  // bit depth
  EXPECT_EQ(bytes[25], 2);  // colour type RGB
  EXPECT_EQ(std::string(bytes.end() - 8, bytes.end() - 4), "IEND");
  if (const char* keep = std::getenv("EFC_KEEP_RENDER")) {
    std::ofstream out(keep, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  }
  std::remove(path.c_str());
  mj_deleteData(d);
  mj_deleteModel(m);
}

TEST(RenderOffscreen, PngToUnwritablePathFailsWithError) {
  mjModel* m = load_xml(scene_xml(0.8, true), "badpath");
  ASSERT_NE(m, nullptr);
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  {
    efc::OffscreenRenderer r(m, 64, 48);
    ASSERT_TRUE(r.ok()) << r.error();
    EXPECT_FALSE(r.render_png(m, d, "/nonexistent_dir_efc/x/frame.png"));
    EXPECT_FALSE(r.error().empty());
  }
  mj_deleteData(d);
  mj_deleteModel(m);
}

TEST(RenderOffscreen, SizeIsClampedToOffscreenBuffer) {
  // Default offscreen buffer is 640x480.
  {
    mjModel* m = load_xml(scene_xml(0.8, true), "clamp_default");
    ASSERT_NE(m, nullptr);
    std::vector<unsigned char> rgb;
    int w = 0, h = 0;
    ASSERT_TRUE(render(m, 4000, 3000, &rgb, &w, &h));
    EXPECT_EQ(w, 640);
    EXPECT_EQ(h, 480);
    mj_deleteModel(m);
  }
  // A model's <global offwidth offheight> bounds it.
  {
    mjModel* m = load_xml(scene_xml(0.8, true, R"(<global offwidth="100" offheight="80"/>)"),
                          "clamp_model");
    ASSERT_NE(m, nullptr);
    std::vector<unsigned char> rgb;
    int w = 0, h = 0;
    ASSERT_TRUE(render(m, 400, 60, &rgb, &w, &h));
    EXPECT_EQ(w, 100);
    EXPECT_EQ(h, 60);
    EXPECT_EQ(rgb.size(), size_t(100) * 60 * 3);
    mj_deleteModel(m);
  }
}

TEST(RenderOffscreen, BrighterLightGivesBrighterImage) {
  double means[2] = {0, 0};
  const double diffuse[2] = {0.15, 0.9};
  for (int i = 0; i < 2; ++i) {
    mjModel* m = load_xml(scene_xml(diffuse[i], true), "light" + std::to_string(i));
    ASSERT_NE(m, nullptr);
    std::vector<unsigned char> rgb;
    int w = 0, h = 0;
    ASSERT_TRUE(render(m, 160, 120, &rgb, &w, &h));
    means[i] = stats(rgb).mean;
    mj_deleteModel(m);
  }
  // Most of the frame is black background, so compare ratios, not levels.
  EXPECT_GT(means[1], 2.0 * means[0] + 1.0) << "dim " << means[0] << " bright " << means[1];
}

TEST(RenderOffscreen, ChangingLightAtRuntimeChangesBrightness) {
  // The harness varies m->light_diffuse during playback (light functions).
  mjModel* m = load_xml(scene_xml(0.1, true), "runtime_light");
  ASSERT_NE(m, nullptr);
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  efc::OffscreenRenderer r(m, 160, 120);
  ASSERT_TRUE(r.ok()) << r.error();
  std::vector<unsigned char> dim, bright;
  int w = 0, h = 0;
  ASSERT_TRUE(r.render_rgb(m, d, &dim, &w, &h)) << r.error();
  int lamp = mj_name2id(m, mjOBJ_LIGHT, "lamp");
  ASSERT_GE(lamp, 0);
  for (int k = 0; k < 3; ++k) m->light_diffuse[3 * lamp + k] = 1.0f;
  ASSERT_TRUE(r.render_rgb(m, d, &bright, &w, &h)) << r.error();
  EXPECT_GT(stats(bright).mean, 2.0 * stats(dim).mean + 1.0)
      << "dim " << stats(dim).mean << " bright " << stats(bright).mean;
  mj_deleteData(d);
  mj_deleteModel(m);
}

}  // namespace
