#pragma once
/// \file counter_rng.h
/// A counter-based random stream: each sample's numbers are a pure function of
/// (seed, direction, step, parent, child), so the reachable sets do not depend on how the
/// samples are spread over threads. SplitMix64 (Steele, Lea, Flood, OOPSLA 2014) hashes the
/// key into a state and then steps it.

#include <cstdint>

namespace reach_trajopt {

/// @brief Per-sample random numbers keyed by (seed, direction, step, parent, child).
class CounterRng {
 public:
  CounterRng(std::uint64_t seed, std::uint64_t direction, std::uint64_t step, std::uint64_t parent,
             std::uint64_t child) {
    std::uint64_t h = mix(seed + 0x9e3779b97f4a7c15ULL);
    h = mix(h ^ (direction + 0x632be59bd9b4e019ULL));
    h = mix(h ^ (step + 0x85157af5ULL));
    h = mix(h ^ (parent + 0x2545f4914f6cdd1dULL));
    state_ = mix(h ^ child);
  }
  /// Next 64 random bits.
  std::uint64_t next() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return mix(state_);
  }
  /// Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  static std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

 private:
  std::uint64_t state_;
};

}  // namespace reach_trajopt
