// Binary erosion and dilation with a disc: a segmenter's outline error is
// isotropic, and a square element would make corners grow faster than
// edges. A disc is a stack of horizontal runs (half-width sqrt(r^2 - dy^2)
// at row offset dy); with a per-row prefix count of set pixels each run is
// tested in O(1), so a radius-r pass costs O(w h r).
#include <algorithm>

#include "synth/image/noise.h"

namespace efc::synth {
namespace {

bool is_grey_image(const seq::Image8& m) {
  return m.width > 0 && m.height > 0 && m.channels == 1 &&
         m.pixels.size() == static_cast<size_t>(m.width) * static_cast<size_t>(m.height);
}

void binarise(seq::Image8* m) {
  for (uint8_t& v : m->pixels) v = v ? 255 : 0;
}

void morph(seq::Image8* mask, int radius, bool dilate) {
  if (!mask || !is_grey_image(*mask)) return;
  if (radius <= 0) {
    binarise(mask);
    return;
  }
  const int w = mask->width, h = mask->height, r = radius;
  // prefix[y (w + 1) + x]: set pixels of row y in columns [0, x).
  std::vector<int> prefix(static_cast<size_t>(w + 1) * h);
  for (int y = 0; y < h; ++y) {
    const uint8_t* row = mask->pixels.data() + static_cast<size_t>(y) * w;
    int* pre = prefix.data() + static_cast<size_t>(y) * (w + 1);
    pre[0] = 0;
    for (int x = 0; x < w; ++x) pre[x + 1] = pre[x] + (row[x] ? 1 : 0);
  }
  // The disc's half-width at each row offset: largest k with k^2 + dy^2 <= r^2.
  std::vector<int> half(2 * r + 1);
  for (int dy = -r; dy <= r; ++dy) {
    int k = 0;
    while ((k + 1) * (k + 1) + dy * dy <= r * r) ++k;
    half[dy + r] = k;
  }
  std::vector<uint8_t> out(mask->pixels.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      bool inside = !dilate;  // dilation: any set pixel; erosion: all set
      for (int dy = -r; dy <= r; ++dy) {
        int yy = y + dy;
        if (yy < 0 || yy >= h) continue;  // outside: no effect either way
        int hw = half[dy + r];
        int x0 = std::max(0, x - hw), x1 = std::min(w - 1, x + hw);
        const int* pre = prefix.data() + static_cast<size_t>(yy) * (w + 1);
        int count = pre[x1 + 1] - pre[x0];
        if (dilate && count > 0) {
          inside = true;
          break;
        }
        if (!dilate && count < x1 - x0 + 1) {
          inside = false;
          break;
        }
      }
      out[static_cast<size_t>(y) * w + x] = inside ? 255 : 0;
    }
  }
  mask->pixels.swap(out);
}

}  // namespace

void dilate_mask(seq::Image8* mask, int radius) { morph(mask, radius, true); }
void erode_mask(seq::Image8* mask, int radius) { morph(mask, radius, false); }

}  // namespace efc::synth
