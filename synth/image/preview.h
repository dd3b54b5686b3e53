// The preview contact sheet of `efc synth`: one frame at a glance, so a
// person can see in one image whether the rendering, the depth and the masks
// line up. Three tiles side by side, each the frame's size:
//   RGB | depth (turbo colormap, near = warm, no reading = black, range the
//        frame's 2nd..98th percentile, written in metres at the bottom) |
//   masks (saturated colours over a darkened grey copy of the RGB, with a
//        legend of the names, each in its mask's colour, in the top-left).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sequence/sequence.h"

namespace efc::synth {

// The sheet as an RGB image of 3 w x h. An empty depth image (0 x 0) draws
// a black tile marked "no depth". False with *error for an RGB frame that is
// not 3-channel of its stated size, a depth or mask of another size than the
// frame, a null mask, a mask that is not 1-channel, or depth_scale <= 0.
bool render_contact_sheet(const seq::Image8& rgb, const seq::Image16& depth, double depth_scale,
                          const std::vector<std::pair<std::string, const seq::Image8*>>& masks,
                          seq::Image8* out, std::string* error);

// render_contact_sheet written as one PNG (seq::write_png_rgb).
bool write_contact_sheet(const std::string& path, const seq::Image8& rgb,
                         const seq::Image16& depth, double depth_scale,
                         const std::vector<std::pair<std::string, const seq::Image8*>>& masks,
                         std::string* error);

// The colour of the index-th mask on the sheet: ten hand-picked saturated
// colours far apart, then hues spaced by the golden angle.
std::array<uint8_t, 3> mask_colour(size_t index);

// Turbo (Mikhailov 2019), x in [0, 1] from dark blue to dark red.
std::array<uint8_t, 3> turbo_colour(double x);

}  // namespace efc::synth
