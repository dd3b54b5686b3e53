// Hand contact-point noise: what a hand detector plus depth lifting reports.
// Gaussian error per axis (mild 3 mm, realistic 8 mm: keypoint error of a few
// pixels times depth noise at arm's length) and missed detections (mild 2 %,
// realistic 6 %: motion blur, the hand half out of view or behind the
// object). One random stream per frame: frames are independent.
#include "synth/image/noise.h"

namespace efc::synth {

std::vector<seq::HandPoint> jitter_hands(const NoiseParams& p,
                                         const std::vector<seq::HandPoint>& truth, uint64_t seed) {
  if (p.hand_sigma_m == 0 && p.hand_miss_prob <= 0) return truth;
  std::vector<seq::HandPoint> out = truth;
  for (size_t i = 0; i < out.size(); ++i) {
    seq::HandPoint& h = out[i];
    if (!h.seen) continue;  // nothing to detect
    Rng rng(stream_seed(seed, i, kHandStream));
    bool missed = rng.chance(p.hand_miss_prob);
    if (missed) {
      h.seen = false;
      h.p = {0, 0, 0};
      continue;
    }
    for (int a = 0; a < 3; ++a) h.p[a] += p.hand_sigma_m * rng.normal();
  }
  return out;
}

}  // namespace efc::synth
