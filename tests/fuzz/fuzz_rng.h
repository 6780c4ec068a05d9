// A seeded, deterministic random source for the FMI call-sequence fuzz. std::mt19937_64 is
// specified bit for bit by the standard; the standard distributions are not (they differ between
// library implementations), so the mappings to ranges are written out here and a seed replays the
// same call sequence with every compiler.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace chaindrive::fuzz {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  std::uint64_t bits() { return engine_(); }

  /// An integer in [0, n); 0 for n == 0. The modulo bias (n / 2^64) is irrelevant here.
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(engine_() % n); }

  /// A double in [0, 1) with 53 random bits.
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  bool chance(double p) { return unit() < p; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  /// Log-uniform in [lo, hi], lo > 0: every decade equally likely.
  double logUniform(double lo, double hi) { return lo * std::pow(hi / lo, unit()); }

  template <class T, std::size_t N>
  const T& pick(const T (&items)[N]) {
    return items[below(N)];
  }
  template <class T>
  const T& pick(const std::vector<T>& items) {
    return items[below(items.size())];
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace chaindrive::fuzz
