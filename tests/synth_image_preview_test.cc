// The preview contact sheet (synth/image/preview.h): RGB | depth | masks.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <unistd.h>

#include "synth/image/preview.h"

namespace efc::synth {
namespace {

constexpr int kW = 160, kH = 120;

struct Frame {
  seq::Image8 rgb;
  seq::Image16 depth;
  seq::Image8 handle, spout;
};

Frame make_frame() {
  Frame f;
  f.rgb = seq::Image8{kW, kH, 3, std::vector<uint8_t>(kW * kH * 3)};
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c)
        f.rgb.pixels[(y * kW + x) * 3 + c] = static_cast<uint8_t>(40 + x + 10 * c);
  // Depth: 0.5 m on the left rising to 2.09 m on the right, a hole at (5, 60).
  f.depth = seq::Image16{kW, kH, std::vector<uint16_t>(kW * kH)};
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) f.depth.pixels[y * kW + x] = static_cast<uint16_t>(500 + 10 * x);
  f.depth.pixels[60 * kW + 5] = 0;
  f.handle = seq::Image8{kW, kH, 1, std::vector<uint8_t>(kW * kH, 0)};
  f.spout = f.handle;
  for (int y = 70; y < 110; ++y)
    for (int x = 20; x < 60; ++x) f.handle.pixels[y * kW + x] = 255;
  for (int y = 70; y < 110; ++y)
    for (int x = 100; x < 140; ++x) f.spout.pixels[y * kW + x] = 255;
  return f;
}

const uint8_t* at(const seq::Image8& img, int x, int y) {
  return img.pixels.data() + (static_cast<size_t>(y) * img.width + x) * 3;
}

TEST(SynthPreview, TheSheetIsThreeFramesWide) {
  Frame f = make_frame();
  seq::Image8 sheet;
  std::string error;
  ASSERT_TRUE(render_contact_sheet(f.rgb, f.depth, 0.001, {{"handle", &f.handle}, {"spout", &f.spout}},
                                   &sheet, &error))
      << error;
  EXPECT_EQ(sheet.width, 3 * kW);
  EXPECT_EQ(sheet.height, kH);
  EXPECT_EQ(sheet.channels, 3);
  ASSERT_EQ(sheet.pixels.size(), static_cast<size_t>(3 * kW * kH * 3));
  // The first tile is the frame itself.
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(at(sheet, x, y)[c], at(f.rgb, x, y)[c]) << x << "," << y;
}

TEST(SynthPreview, DepthIsWarmNearColdFarBlackWhereMissing) {
  Frame f = make_frame();
  seq::Image8 sheet;
  std::string error;
  ASSERT_TRUE(render_contact_sheet(f.rgb, f.depth, 0.001, {}, &sheet, &error)) << error;
  const uint8_t* near = at(sheet, kW + 2, 40);
  // 85 % of the way to the far end: turbo's blue (its very end is dark purple).
  const uint8_t* far = at(sheet, kW + 133, 40);
  const uint8_t* hole = at(sheet, kW + 5, 60);
  EXPECT_GT(near[0], near[2] + 60);  // red
  EXPECT_GT(far[2], far[0] + 60);    // blue
  EXPECT_EQ(hole[0] + hole[1] + hole[2], 0);
  // Mid-range is neither end: turbo's green-yellow middle.
  const uint8_t* mid = at(sheet, kW + kW / 2, 40);
  EXPECT_GT(mid[1], 150);
  // The range label (white text on near-black) sits at the bottom left.
  int white = 0;
  for (int y = kH - 22; y < kH; ++y)
    for (int x = kW; x < kW + 120; ++x) white += at(sheet, x, y)[0] == 255 && at(sheet, x, y)[2] == 255;
  EXPECT_GT(white, 20);
}

TEST(SynthPreview, MasksAreColouredAndTheLegendUsesTheirColours) {
  Frame f = make_frame();
  seq::Image8 sheet;
  std::string error;
  ASSERT_TRUE(render_contact_sheet(f.rgb, f.depth, 0.001, {{"handle", &f.handle}, {"spout", &f.spout}},
                                   &sheet, &error))
      << error;
  const auto c0 = mask_colour(0), c1 = mask_colour(1);
  ASSERT_NE(c0, c1);
  // Inside a mask the colour dominates the darkened grey.
  const uint8_t* in_handle = at(sheet, 2 * kW + 40, 90);
  const uint8_t* outside = at(sheet, 2 * kW + 80, 90);
  EXPECT_GT(in_handle[0], outside[0] + 60);
  EXPECT_EQ(outside[0], outside[1]);  // grey
  EXPECT_LT(outside[0], at(f.rgb, 80, 90)[1]);  // darkened
  // Legend, top left of the mask tile: line k (18 px high from y = 4) has the
  // name's text in colour k to the right of its swatch.
  auto text_pixels = [&](int line, const std::array<uint8_t, 3>& colour) {
    int n = 0;
    for (int y = 4 + 18 * line; y < 4 + 18 * line + 14; ++y)
      for (int x = 2 * kW + 4 + 14 + 4; x < 3 * kW; ++x) {
        const uint8_t* p = at(sheet, x, y);
        n += p[0] == colour[0] && p[1] == colour[1] && p[2] == colour[2];
      }
    return n;
  };
  EXPECT_GT(text_pixels(0, c0), 40);   // "handle"
  EXPECT_GT(text_pixels(1, c1), 40);   // "spout"
  EXPECT_EQ(text_pixels(0, c1), 0);
  EXPECT_EQ(text_pixels(1, c0), 0);
  // Nothing of the legend spills into the depth tile.
  EXPECT_NE(at(sheet, 2 * kW - 1, 5)[0], c0[0]);
}

TEST(SynthPreview, MaskColoursAreDistinct) {
  for (size_t a = 0; a < 24; ++a)
    for (size_t b = a + 1; b < 24; ++b) EXPECT_NE(mask_colour(a), mask_colour(b)) << a << " " << b;
}

TEST(SynthPreview, BadInputsAreErrorsNotCrashes) {
  Frame f = make_frame();
  seq::Image8 sheet;
  std::string error;
  EXPECT_FALSE(render_contact_sheet(f.rgb, f.depth, 0.001, {{"handle", nullptr}}, &sheet, &error));
  EXPECT_NE(error.find("handle"), std::string::npos) << error;

  seq::Image8 small{10, 10, 1, std::vector<uint8_t>(100, 255)};
  error.clear();
  EXPECT_FALSE(render_contact_sheet(f.rgb, f.depth, 0.001, {{"spout", &small}}, &sheet, &error));
  EXPECT_NE(error.find("spout"), std::string::npos) << error;

  seq::Image8 short_mask{kW, kH, 1, {}};
  EXPECT_FALSE(render_contact_sheet(f.rgb, f.depth, 0.001, {{"spout", &short_mask}}, &sheet, &error));

  seq::Image8 grey_rgb{kW, kH, 1, std::vector<uint8_t>(kW * kH)};
  EXPECT_FALSE(render_contact_sheet(grey_rgb, f.depth, 0.001, {}, &sheet, &error));
  seq::Image8 truncated = f.rgb;
  truncated.pixels.resize(10);
  EXPECT_FALSE(render_contact_sheet(truncated, f.depth, 0.001, {}, &sheet, &error));

  seq::Image16 bad_depth{kW, kH - 1, std::vector<uint16_t>(kW * (kH - 1))};
  EXPECT_FALSE(render_contact_sheet(f.rgb, bad_depth, 0.001, {}, &sheet, &error));
  EXPECT_FALSE(render_contact_sheet(f.rgb, f.depth, 0.0, {}, &sheet, &error));
  EXPECT_FALSE(render_contact_sheet(f.rgb, f.depth, 0.001, {}, nullptr, &error));
  EXPECT_FALSE(render_contact_sheet(f.rgb, f.depth, 0.001, {{"x", nullptr}}, &sheet, nullptr));

  // No depth at all is a black tile, not an error.
  EXPECT_TRUE(render_contact_sheet(f.rgb, seq::Image16{}, 0.001, {}, &sheet, &error)) << error;
  EXPECT_EQ(at(sheet, kW + kW / 2, kH / 2)[0], 0);

  EXPECT_FALSE(write_contact_sheet("/nonexistent-dir/x/sheet.png", f.rgb, f.depth, 0.001, {},
                                   &error));
  EXPECT_FALSE(error.empty());
}

TEST(SynthPreview, WritesOnePngOfTheSheet) {
  Frame f = make_frame();
  const std::string path =
      ::testing::TempDir() + "/efc_contact_sheet_" + std::to_string(getpid()) + ".png";
  std::string error;
  ASSERT_TRUE(write_contact_sheet(path, f.rgb, f.depth, 0.001,
                                  {{"handle", &f.handle}, {"spout", &f.spout}}, &error))
      << error;
  seq::Image8 read, rendered;
  ASSERT_TRUE(seq::read_png_rgb(path, &read, &error)) << error;
  ASSERT_TRUE(render_contact_sheet(f.rgb, f.depth, 0.001, {{"handle", &f.handle}, {"spout", &f.spout}},
                                   &rendered, &error));
  EXPECT_EQ(read.width, 3 * kW);
  EXPECT_EQ(read.height, kH);
  EXPECT_EQ(read.pixels, rendered.pixels);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace efc::synth
