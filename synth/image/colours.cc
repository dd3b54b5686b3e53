// Colours of the preview: the turbo colormap for depth and the mask palette.
#include <algorithm>
#include <cmath>

#include "synth/image/preview.h"

namespace efc::synth {
namespace {

uint8_t to_byte(double v) {
  return static_cast<uint8_t>(std::lround(255.0 * std::min(1.0, std::max(0.0, v))));
}

}  // namespace

std::array<uint8_t, 3> turbo_colour(double x) {
  // Turbo: a rainbow made perceptually smoother than jet (no false bands),
  // which reads depth order at a glance. Polynomial fit by Ruofei Du
  // (Copyright 2019 Google LLC, Apache-2.0) of Anton Mikhailov's table.
  x = std::min(1.0, std::max(0.0, x));
  double r = 0.13572138 + x * (4.61539260 + x * (-42.66032258 + x * (132.13108234 +
             x * (-152.94239396 + x * 59.28637943))));
  double g = 0.09140261 + x * (2.19418839 + x * (4.84296658 + x * (-14.18503333 +
             x * (4.27729857 + x * 2.82956604))));
  double b = 0.10667330 + x * (12.64194608 + x * (-60.58204836 + x * (110.36276771 +
             x * (-89.90310912 + x * 27.34824973))));
  return {to_byte(r), to_byte(g), to_byte(b)};
}

std::array<uint8_t, 3> mask_colour(size_t index) {
  // Distinct at a glance against grey and against each other.
  static const std::array<uint8_t, 3> kPalette[] = {
      {230, 25, 75},   // red
      {60, 200, 75},   // green
      {0, 130, 230},   // blue
      {255, 225, 25},  // yellow
      {245, 130, 48},  // orange
      {170, 40, 220},  // purple
      {70, 240, 240},  // cyan
      {240, 50, 230},  // magenta
      {190, 245, 60},  // lime
      {255, 150, 190}, // pink
  };
  constexpr size_t kCount = sizeof(kPalette) / sizeof(kPalette[0]);
  if (index < kCount) return kPalette[index];
  // Fully saturated hues, the golden angle apart, never repeating exactly.
  double h = std::fmod(0.61803398875 * static_cast<double>(index - kCount) + 0.11, 1.0) * 6.0;
  int sector = static_cast<int>(h) % 6;
  double f = h - std::floor(h);
  double rgb[6][3] = {{1, f, 0}, {1 - f, 1, 0}, {0, 1, f}, {0, 1 - f, 1}, {f, 0, 1}, {1, 0, 1 - f}};
  return {to_byte(rgb[sector][0]), to_byte(rgb[sector][1]), to_byte(rgb[sector][2])};
}

}  // namespace efc::synth
