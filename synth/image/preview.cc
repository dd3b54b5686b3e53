// The contact sheet: RGB | depth | masks, one PNG per previewed frame.
#include "synth/image/preview.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "synth/image/bitmap_font.h"

namespace efc::synth {
namespace {

constexpr int kFontScale = 2;  // 5x7 glyphs drawn 10x14: readable at 640x480
constexpr int kLineHeight = kGlyphHeight * kFontScale + 4;
constexpr int kMargin = 4;

bool fail(std::string* error, const std::string& message) {
  if (error) *error = message;
  return false;
}

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

uint8_t luma(const uint8_t* p) {
  return static_cast<uint8_t>((77 * p[0] + 150 * p[1] + 29 * p[2] + 128) >> 8);
}

uint8_t* pixel(seq::Image8* img, int x, int y) {
  return img->pixels.data() + (static_cast<size_t>(y) * img->width + x) * 3;
}

void fill_rect(seq::Image8* img, int x0, int y0, int x1, int y1,
               const std::array<uint8_t, 3>& colour) {
  x0 = std::max(0, x0), y0 = std::max(0, y0);
  x1 = std::min(img->width, x1), y1 = std::min(img->height, y1);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      uint8_t* p = pixel(img, x, y);
      p[0] = colour[0], p[1] = colour[1], p[2] = colour[2];
    }
  }
}

// A label in the corner of a tile, on a near-black box so it reads over anything.
void draw_label(seq::Image8* sheet, int tile_x0, int tile_x1, int x, int y,
                const std::string& text, const std::array<uint8_t, 3>& colour) {
  fill_rect(sheet, std::max(tile_x0, x - 2), y - 2,
            std::min(tile_x1, x + text_width(text, kFontScale) + 2),
            y + kGlyphHeight * kFontScale + 2, {16, 16, 16});
  draw_text(sheet, x, y, text, colour, kFontScale, tile_x0, tile_x1);
}

void draw_rgb_tile(const seq::Image8& rgb, seq::Image8* sheet) {
  const int w = rgb.width;
  for (int y = 0; y < rgb.height; ++y) {
    std::copy_n(rgb.pixels.data() + static_cast<size_t>(y) * w * 3, static_cast<size_t>(w) * 3,
                pixel(sheet, 0, y));
  }
}

// Depth in turbo, near = warm, over the frame's 2nd..98th percentile so a
// few far background pixels do not wash the object out.
void draw_depth_tile(const seq::Image16& depth, double depth_scale, int w, int h,
                     seq::Image8* sheet) {
  const int x_off = w;
  if (depth.pixels.empty()) {
    draw_label(sheet, x_off, 2 * w, x_off + kMargin, h - kMargin - kGlyphHeight * kFontScale,
               "no depth", {255, 255, 255});
    return;
  }
  std::vector<uint16_t> valid;
  valid.reserve(depth.pixels.size());
  for (uint16_t v : depth.pixels) {
    if (v) valid.push_back(v);
  }
  if (valid.empty()) {
    draw_label(sheet, x_off, 2 * w, x_off + kMargin, h - kMargin - kGlyphHeight * kFontScale,
               "no readings", {255, 255, 255});
    return;
  }
  const size_t lo_i = (valid.size() - 1) * 2 / 100, hi_i = (valid.size() - 1) * 98 / 100;
  std::nth_element(valid.begin(), valid.begin() + lo_i, valid.end());
  const double lo = valid[lo_i];
  std::nth_element(valid.begin(), valid.begin() + hi_i, valid.end());
  const double hi = std::max(lo + 1.0, static_cast<double>(valid[hi_i]));

  std::array<std::array<uint8_t, 3>, 256> lut;
  for (int k = 0; k < 256; ++k) lut[k] = turbo_colour(k / 255.0);
  const double to_index = 255.0 / (hi - lo);
  for (int y = 0; y < h; ++y) {
    const uint16_t* row = depth.pixels.data() + static_cast<size_t>(y) * w;
    for (int x = 0; x < w; ++x) {
      uint8_t* p = pixel(sheet, x_off + x, y);
      if (!row[x]) {
        p[0] = p[1] = p[2] = 0;
        continue;
      }
      double t = std::min(255.0, std::max(0.0, (row[x] - lo) * to_index));
      const auto& c = lut[255 - static_cast<int>(t + 0.5)];  // near = warm end
      p[0] = c[0], p[1] = c[1], p[2] = c[2];
    }
  }
  char range[64];
  std::snprintf(range, sizeof range, "%.2f-%.2fm", lo * depth_scale, hi * depth_scale);
  draw_label(sheet, x_off, 2 * w, x_off + kMargin, h - kMargin - kGlyphHeight * kFontScale,
             range, {255, 255, 255});
}

// Masks over a darkened grey copy of the frame (the colours must dominate),
// later masks on top, then the legend.
void draw_mask_tile(const seq::Image8& rgb,
                    const std::vector<std::pair<std::string, const seq::Image8*>>& masks,
                    seq::Image8* sheet) {
  const int w = rgb.width, h = rgb.height, x_off = 2 * w;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      uint8_t g = static_cast<uint8_t>(luma(rgb.pixels.data() + (static_cast<size_t>(y) * w + x) * 3) * 2 / 5);
      uint8_t* p = pixel(sheet, x_off + x, y);
      p[0] = p[1] = p[2] = g;
    }
  }
  for (size_t k = 0; k < masks.size(); ++k) {
    const auto colour = mask_colour(k);
    const uint8_t* m = masks[k].second->pixels.data();
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        if (!m[static_cast<size_t>(y) * w + x]) continue;
        uint8_t* p = pixel(sheet, x_off + x, y);
        for (int c = 0; c < 3; ++c) p[c] = static_cast<uint8_t>((2 * p[c] + 3 * colour[c]) / 5);
      }
    }
  }
  // Legend: a swatch and the name in the mask's colour, one line per mask.
  int widest = 0;
  for (const auto& [name, image] : masks) widest = std::max(widest, text_width(name, kFontScale));
  if (masks.empty()) return;
  const int swatch = kGlyphHeight * kFontScale;
  fill_rect(sheet, x_off, 0, x_off + 2 * kMargin + swatch + kMargin + widest,
            2 * kMargin + static_cast<int>(masks.size()) * kLineHeight - 4, {16, 16, 16});
  for (size_t k = 0; k < masks.size(); ++k) {
    const auto colour = mask_colour(k);
    const int y = kMargin + static_cast<int>(k) * kLineHeight;
    const int x = x_off + kMargin;
    fill_rect(sheet, x, y, std::min(x + swatch, 3 * w), y + swatch, colour);
    draw_text(sheet, x + swatch + kMargin, y, masks[k].first, colour, kFontScale, x_off, 3 * w);
  }
}

}  // namespace

bool render_contact_sheet(const seq::Image8& rgb, const seq::Image16& depth, double depth_scale,
                          const std::vector<std::pair<std::string, const seq::Image8*>>& masks,
                          seq::Image8* out, std::string* error) {
  if (!out) return fail(error, "contact sheet: no output image");
  const int w = rgb.width, h = rgb.height;
  if (w <= 0 || h <= 0 || rgb.channels != 3 ||
      rgb.pixels.size() != static_cast<size_t>(w) * h * 3) {
    return fail(error, "contact sheet: the RGB frame is not a " + size_text(w, h) +
                           " 3-channel image (channels " + std::to_string(rgb.channels) +
                           ", " + std::to_string(rgb.pixels.size()) + " bytes)");
  }
  const bool no_depth = depth.width == 0 && depth.height == 0 && depth.pixels.empty();
  if (!no_depth && (depth.width != w || depth.height != h ||
                    depth.pixels.size() != static_cast<size_t>(w) * h)) {
    return fail(error, "contact sheet: depth is " + size_text(depth.width, depth.height) +
                           " with " + std::to_string(depth.pixels.size()) +
                           " values, expected " + size_text(w, h));
  }
  if (!(depth_scale > 0) || !std::isfinite(depth_scale)) {
    return fail(error, "contact sheet: depth_scale must be positive");
  }
  for (const auto& [name, mask] : masks) {
    if (!mask) return fail(error, "contact sheet: mask '" + name + "' has no image");
    if (mask->width != w || mask->height != h || mask->channels != 1 ||
        mask->pixels.size() != static_cast<size_t>(w) * h) {
      return fail(error, "contact sheet: mask '" + name + "' is " +
                             size_text(mask->width, mask->height) + " with " +
                             std::to_string(mask->channels) + " channel(s), expected " +
                             size_text(w, h) + " grey");
    }
  }
  seq::Image8 sheet;
  sheet.width = 3 * w;
  sheet.height = h;
  sheet.channels = 3;
  sheet.pixels.assign(static_cast<size_t>(sheet.width) * h * 3, 0);
  draw_rgb_tile(rgb, &sheet);
  draw_depth_tile(depth, depth_scale, w, h, &sheet);
  draw_mask_tile(rgb, masks, &sheet);
  *out = std::move(sheet);
  return true;
}

bool write_contact_sheet(const std::string& path, const seq::Image8& rgb,
                         const seq::Image16& depth, double depth_scale,
                         const std::vector<std::pair<std::string, const seq::Image8*>>& masks,
                         std::string* error) {
  seq::Image8 sheet;
  if (!render_contact_sheet(rgb, depth, depth_scale, masks, &sheet, error)) return false;
  std::string why;  // names the path already
  if (!seq::write_png_rgb(path, sheet, &why)) return fail(error, why);
  return true;
}

}  // namespace efc::synth
