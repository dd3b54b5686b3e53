// Deterministic random numbers for the suite plan.
//
// The plan must give the same bytes for the same seed with every standard
// library, and std::*_distribution is implementation-defined. So only
// std::mt19937_64's raw output is used (the standard fixes its sequence) and
// every distribution is written here with + - * / only (no libm: its last
// bits may differ between platforms).
#pragma once

#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace efc::synth::suite {

// splitmix64's finaliser: derives unrelated seeds from (seed, index, stream),
// so entry i of a plan depends only on (seed, i) and each aspect of an entry
// (its spec, its knobs, ...) draws from its own stream.
inline uint64_t mix_seed(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

inline uint64_t derive_seed(uint64_t seed, uint64_t index, uint64_t stream) {
  uint64_t h = mix_seed(seed ^ 0x243f6a8885a308d3ULL);
  h = mix_seed(h ^ (index + 0x9e3779b97f4a7c15ULL));
  return mix_seed(h ^ (stream + 0xd1b54a32d192ed03ULL));
}

class SuiteRng {
 public:
  explicit SuiteRng(uint64_t seed) : engine_(seed) {}

  // [0, 1) with 53 random bits.
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  bool chance(double p) { return unit() < p; }
  // An integer in [lo, hi] (hi >= lo). The modulo bias (< 2^-50 here) is
  // irrelevant for a benchmark's choices.
  int between(int lo, int hi) {
    const uint64_t span = static_cast<uint64_t>(static_cast<int64_t>(hi) - lo) + 1;
    return lo + static_cast<int>(engine_() % span);
  }
  size_t index(size_t n) { return static_cast<size_t>(between(0, static_cast<int>(n) - 1)); }
  template <class T>
  const T& pick(const std::vector<T>& items) {
    return items[index(items.size())];
  }
  // An index drawn with the given non-negative weights (not all zero).
  size_t weighted(const std::vector<double>& weights) {
    double total = 0;
    for (double w : weights) total += w;
    double x = unit() * total;
    for (size_t i = 0; i < weights.size(); ++i) {
      if (x < weights[i]) return i;
      x -= weights[i];
    }
    return weights.size() - 1;  // x == total after rounding
  }
  template <class T>
  void shuffle(std::vector<T>& items) {
    for (size_t i = items.size(); i > 1; --i) std::swap(items[i - 1], items[index(i)]);
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace efc::synth::suite
