// A tiny embedded 5x7 bitmap font for labels on preview images (the mask
// legend, the depth range): lower-case letters, digits and _ + - . ; upper
// case is drawn as lower case, anything else as '?'. No font files, no
// dependencies.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "sequence/sequence.h"

namespace efc::synth {

constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 7;

// Pixel advance of one character and the width of a whole string at `scale`
// (one blank column between characters, none after the last).
inline int glyph_advance(int scale) { return (kGlyphWidth + 1) * scale; }
int text_width(const std::string& text, int scale);

// Draws `text` into an RGB image with its top-left corner at (x, y), each
// font pixel a scale x scale block of `colour`. Only pixels with
// clip_x0 <= px < clip_x1 (and inside the image) are touched.
void draw_text(seq::Image8* img, int x, int y, const std::string& text,
               const std::array<uint8_t, 3>& colour, int scale, int clip_x0, int clip_x1);

}  // namespace efc::synth
