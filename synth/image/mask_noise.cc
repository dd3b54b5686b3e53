// Segmentation noise: what an instance segmenter / video tracker delivers.
//  - outline error: each mask eroded or dilated by 0..r pixels (mild 1,
//    realistic 2): boundaries are where networks are least sure, and the
//    error is a band a pixel or two wide, biased in or out per instance;
//  - missed frames: a mask is lost for one frame (mild 1 %, realistic 3 %)
//    under blur or occlusion;
//  - identity switches: two similar instances' masks exchanged for one frame
//    (realistic 1.5 %, mild never), only between the pairs the caller names.
// Every decision is seeded by (seed, frame, stream, mask name), never by a
// running state, so a frame processed alone equals the same frame in a batch.
#include <algorithm>

#include "synth/image/noise.h"

namespace efc::synth {
namespace {

// FNV-1a: a mask's stream depends on its name, not on its place in the set.
uint64_t name_hash(const std::string& s) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : s) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

bool is_grey_image(const seq::Image8& m) {
  return m.width > 0 && m.height > 0 && m.channels == 1 &&
         m.pixels.size() == static_cast<size_t>(m.width) * static_cast<size_t>(m.height);
}

}  // namespace

MaskNoiseLog add_mask_noise(const NoiseParams& p, int frame, MaskSet* set,
                            const std::vector<std::pair<int, int>>& swap_pairs, uint64_t seed) {
  MaskNoiseLog log;
  log.frame = frame;
  if (!set) return log;
  const int n = static_cast<int>(std::min(set->names.size(), set->masks.size()));
  const uint64_t frame_u = static_cast<uint64_t>(static_cast<int64_t>(frame));

  if (p.mask_swap_prob > 0 && !swap_pairs.empty()) {
    Rng rng(stream_seed(seed, frame_u, kMaskSwapStream));
    if (rng.chance(p.mask_swap_prob)) {
      const auto& pair = swap_pairs[rng.integer(0, static_cast<int>(swap_pairs.size()) - 1)];
      int a = pair.first, b = pair.second;
      if (a >= 0 && b >= 0 && a < n && b < n && a != b) {
        std::swap(set->masks[a], set->masks[b]);
        log.swapped.emplace_back(set->names[a], set->names[b]);
      }
    }
  }

  if (p.mask_miss_prob <= 0 && p.mask_radius_px <= 0) return log;
  for (int k = 0; k < n; ++k) {
    seq::Image8& mask = set->masks[k];
    const std::string& name = set->names[k];
    if (!is_grey_image(mask)) continue;
    Rng rng(stream_seed(stream_seed(seed, frame_u, kMaskStream), name_hash(name)));
    // Same draws whatever is decided: the radius does not depend on the miss.
    bool missed = rng.chance(p.mask_miss_prob);
    int radius = rng.integer(0, std::max(0, p.mask_radius_px));
    bool grow = rng.chance(0.5);
    if (missed) {
      std::fill(mask.pixels.begin(), mask.pixels.end(), 0);
      log.missed.push_back(name);
    } else if (radius > 0 && grow) {
      dilate_mask(&mask, radius);
      log.dilated.push_back(name);
      log.dilated_px.push_back(radius);
    } else if (radius > 0) {
      erode_mask(&mask, radius);
      log.eroded.push_back(name);
      log.eroded_px.push_back(radius);
    }
  }
  return log;
}

}  // namespace efc::synth
