// Deterministic random numbers for the synthetic sensor noise.
//
// The standard library's distributions (std::normal_distribution, ...) are
// implementation-defined: the same seed gives other numbers with another
// standard library. A synthetic benchmark must give the same bytes for the
// same seed everywhere, so everything here is our own arithmetic on 64-bit
// integers: splitmix64 (Steele, Lea, Flood 2014) as the generator and its
// finaliser as the hash that derives independent streams.
//
// stream_seed(seed, frame, stream) lets every frame and every noise model
// draw from its own stream, so frames can be processed in any order, in any
// thread, and still give identical output.
#pragma once

#include <cmath>
#include <cstdint>

namespace efc::synth {

// splitmix64's output function: a bijective 64-bit mixer with full avalanche.
inline uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// One step of splitmix64: advances *state by the golden-ratio increment and
// returns the mixed value.
inline uint64_t splitmix64(uint64_t* state) {
  *state += 0x9e3779b97f4a7c15ULL;
  return mix64(*state);
}

// A seed for one (frame, stream) of a sequence generated from `seed`. Each
// input goes through the mixer before the next is folded in, so (seed, a, b)
// and (seed, b, a) or (seed + 1, a - 1, b) are unrelated streams.
inline uint64_t stream_seed(uint64_t seed, uint64_t a, uint64_t b = 0) {
  uint64_t h = mix64(seed ^ 0x243f6a8885a308d3ULL);  // pi's digits: any odd constant
  h = mix64(h ^ (a + 0x9e3779b97f4a7c15ULL));
  h = mix64(h ^ (b + 0xd1b54a32d192ed03ULL));
  return h;
}

// A stream of numbers from one 64-bit seed. Cheap to construct (one word of
// state), so a fresh Rng per frame and stream is the intended use.
class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}

  uint64_t next() { return splitmix64(&state_); }

  // [0, 1) with 53 random bits: every double is a multiple of 2^-53.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  // Standard normal by the Box-Muller transform; the second value of each
  // pair is kept for the next call (half the logs and square roots).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = 1.0 - uniform();  // (0, 1]: log(u1) is finite
    double u2 = uniform();
    double r = std::sqrt(-2.0 * std::log(u1));
    double a = 6.283185307179586 * u2;
    spare_ = r * std::sin(a);
    has_spare_ = true;
    return r * std::cos(a);
  }

  // True with probability p (never for p <= 0, always for p >= 1).
  bool chance(double p) { return uniform() < p; }

  // Uniform integer in [lo, hi], both included (lo when hi < lo). Lemire's
  // multiply-shift with rejection: no modulo bias.
  int integer(int lo, int hi) {
    if (hi <= lo) return lo;
    uint64_t range = static_cast<uint64_t>(static_cast<int64_t>(hi) - lo) + 1;
    uint64_t threshold = (0 - range) % range;  // 2^64 mod range
    for (;;) {
      unsigned __int128 m = static_cast<unsigned __int128>(next()) * range;
      if (static_cast<uint64_t>(m) >= threshold) {
        return static_cast<int>(lo + static_cast<int64_t>(m >> 64));
      }
    }
  }

 private:
  uint64_t state_;
  double spare_ = 0;
  bool has_spare_ = false;
};

}  // namespace efc::synth
