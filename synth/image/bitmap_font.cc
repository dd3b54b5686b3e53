// The glyphs: 7 rows of 5 bits each, the leftmost pixel in bit 4.
#include "synth/image/bitmap_font.h"

#include <algorithm>
#include <cctype>

namespace efc::synth {
namespace {

using Glyph = std::array<uint8_t, kGlyphHeight>;

const Glyph& glyph(char c) {
  static const Glyph kLetters[26] = {
      {0b00000, 0b00000, 0b01110, 0b00001, 0b01111, 0b10001, 0b01111},  // a
      {0b10000, 0b10000, 0b10110, 0b11001, 0b10001, 0b10001, 0b11110},  // b
      {0b00000, 0b00000, 0b01110, 0b10000, 0b10000, 0b10001, 0b01110},  // c
      {0b00001, 0b00001, 0b01101, 0b10011, 0b10001, 0b10001, 0b01111},  // d
      {0b00000, 0b00000, 0b01110, 0b10001, 0b11111, 0b10000, 0b01110},  // e
      {0b00110, 0b01001, 0b01000, 0b11100, 0b01000, 0b01000, 0b01000},  // f
      {0b00000, 0b01111, 0b10001, 0b10001, 0b01111, 0b00001, 0b01110},  // g
      {0b10000, 0b10000, 0b10110, 0b11001, 0b10001, 0b10001, 0b10001},  // h
      {0b00100, 0b00000, 0b01100, 0b00100, 0b00100, 0b00100, 0b01110},  // i
      {0b00010, 0b00000, 0b00110, 0b00010, 0b00010, 0b10010, 0b01100},  // j
      {0b10000, 0b10000, 0b10010, 0b10100, 0b11000, 0b10100, 0b10010},  // k
      {0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110},  // l
      {0b00000, 0b00000, 0b11010, 0b10101, 0b10101, 0b10001, 0b10001},  // m
      {0b00000, 0b00000, 0b10110, 0b11001, 0b10001, 0b10001, 0b10001},  // n
      {0b00000, 0b00000, 0b01110, 0b10001, 0b10001, 0b10001, 0b01110},  // o
      {0b00000, 0b00000, 0b11110, 0b10001, 0b11110, 0b10000, 0b10000},  // p
      {0b00000, 0b00000, 0b01101, 0b10011, 0b01111, 0b00001, 0b00001},  // q
      {0b00000, 0b00000, 0b10110, 0b11001, 0b10000, 0b10000, 0b10000},  // r
      {0b00000, 0b00000, 0b01110, 0b10000, 0b01110, 0b00001, 0b11110},  // s
      {0b01000, 0b01000, 0b11100, 0b01000, 0b01000, 0b01001, 0b00110},  // t
      {0b00000, 0b00000, 0b10001, 0b10001, 0b10001, 0b10011, 0b01101},  // u
      {0b00000, 0b00000, 0b10001, 0b10001, 0b10001, 0b01010, 0b00100},  // v
      {0b00000, 0b00000, 0b10001, 0b10001, 0b10101, 0b10101, 0b01010},  // w
      {0b00000, 0b00000, 0b10001, 0b01010, 0b00100, 0b01010, 0b10001},  // x
      {0b00000, 0b00000, 0b10001, 0b10001, 0b01111, 0b00001, 0b01110},  // y
      {0b00000, 0b00000, 0b11111, 0b00010, 0b00100, 0b01000, 0b11111},  // z
  };
  static const Glyph kDigits[10] = {
      {0b01110, 0b10001, 0b10011, 0b10101, 0b11001, 0b10001, 0b01110},  // 0
      {0b00100, 0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110},  // 1
      {0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0b01000, 0b11111},  // 2
      {0b11111, 0b00010, 0b00100, 0b00010, 0b00001, 0b10001, 0b01110},  // 3
      {0b00010, 0b00110, 0b01010, 0b10010, 0b11111, 0b00010, 0b00010},  // 4
      {0b11111, 0b10000, 0b11110, 0b00001, 0b00001, 0b10001, 0b01110},  // 5
      {0b00110, 0b01000, 0b10000, 0b11110, 0b10001, 0b10001, 0b01110},  // 6
      {0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b01000, 0b01000},  // 7
      {0b01110, 0b10001, 0b10001, 0b01110, 0b10001, 0b10001, 0b01110},  // 8
      {0b01110, 0b10001, 0b10001, 0b01111, 0b00001, 0b00010, 0b01100},  // 9
  };
  static const Glyph kUnderscore = {0, 0, 0, 0, 0, 0, 0b11111};
  static const Glyph kPlus = {0, 0b00100, 0b00100, 0b11111, 0b00100, 0b00100, 0};
  static const Glyph kMinus = {0, 0, 0, 0b11111, 0, 0, 0};
  static const Glyph kDot = {0, 0, 0, 0, 0, 0b01100, 0b01100};
  static const Glyph kSpace = {0, 0, 0, 0, 0, 0, 0};
  static const Glyph kUnknown = {0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0, 0b00100};

  unsigned char u = static_cast<unsigned char>(c);
  if (std::isupper(u)) u = static_cast<unsigned char>(std::tolower(u));
  if (u >= 'a' && u <= 'z') return kLetters[u - 'a'];
  if (u >= '0' && u <= '9') return kDigits[u - '0'];
  switch (u) {
    case '_': return kUnderscore;
    case '+': return kPlus;
    case '-': return kMinus;
    case '.': return kDot;
    case ' ': return kSpace;
    default: return kUnknown;
  }
}

}  // namespace

int text_width(const std::string& text, int scale) {
  if (text.empty()) return 0;
  return static_cast<int>(text.size()) * glyph_advance(scale) - scale;
}

void draw_text(seq::Image8* img, int x, int y, const std::string& text,
               const std::array<uint8_t, 3>& colour, int scale, int clip_x0, int clip_x1) {
  if (!img || img->channels != 3 || scale <= 0) return;
  const int w = img->width, h = img->height;
  if (img->pixels.size() != static_cast<size_t>(w) * h * 3) return;
  const int x_lo = std::max(0, clip_x0), x_hi = std::min(w, clip_x1);
  for (size_t k = 0; k < text.size(); ++k) {
    const Glyph& g = glyph(text[k]);
    const int gx = x + static_cast<int>(k) * glyph_advance(scale);
    for (int row = 0; row < kGlyphHeight; ++row) {
      for (int col = 0; col < kGlyphWidth; ++col) {
        if (!(g[row] & (0x10 >> col))) continue;
        for (int sy = 0; sy < scale; ++sy) {
          const int py = y + row * scale + sy;
          if (py < 0 || py >= h) continue;
          for (int sx = 0; sx < scale; ++sx) {
            const int px = gx + col * scale + sx;
            if (px < x_lo || px >= x_hi) continue;
            uint8_t* p = img->pixels.data() + (static_cast<size_t>(py) * w + px) * 3;
            p[0] = colour[0];
            p[1] = colour[1];
            p[2] = colour[2];
          }
        }
      }
    }
  }
}

}  // namespace efc::synth
