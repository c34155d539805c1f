#pragma once
// The soak test's only source of randomness. SplitMix64 and our own mappings to ranges, not
// <random>'s distributions: the standard fixes mt19937's output but not how
// uniform_int_distribution and friends use it, so a seed would mean another sequence under
// another standard library, and a failure found on one machine could not be replayed on another.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "physics/types.h"

namespace soak {

class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}

  /// SplitMix64 (Steele, Lea and Flood 2014): every seed, 0 included, gives a full-period stream.
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

  /// Uniform in [0, 1), from the top 53 bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform in [lo, hi], both included. The modulo's bias is below 2^-40 for our ranges.
  int integer(int lo, int hi) {
    const auto span = static_cast<std::uint64_t>(static_cast<std::int64_t>(hi) - lo + 1);
    return static_cast<int>(lo + static_cast<std::int64_t>(next() % span));
  }
  std::size_t index(std::size_t size) { return static_cast<std::size_t>(next() % size); }
  bool chance(double p) { return uniform() < p; }
  /// Log-uniform in [lo, hi], lo > 0: as many draws between 1e-6 and 1e-5 as between 0.1 and 1.
  double logUniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  /// Log-uniform whole number in [lo, hi], lo >= 1.
  int logInteger(int lo, int hi) {
    const double v = std::floor(logUniform(lo, hi + 1.0));
    return static_cast<int>(std::min(v, static_cast<double>(hi)));
  }
  /// A direction uniform on the sphere (rejection from the cube, so no trigonometry to differ).
  phys::Vec3 unitVector() {
    for (;;) {
      const phys::Vec3 v{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};  // braces: drawn in order
      const double length = glm::length(v);
      if (length > 1e-3 && length <= 1.0) return v / length;
    }
  }
  template <class T>
  const T& pick(const std::vector<T>& items) {
    return items[index(items.size())];
  }
  template <class T>
  void shuffle(std::vector<T>& items) {  // Fisher-Yates
    for (std::size_t i = items.size(); i > 1; --i) std::swap(items[i - 1], items[index(i)]);
  }

 private:
  std::uint64_t state_;
};

}  // namespace soak
