#pragma once
// Seeds of a run's independent companions (the repeats of a transport measurement): a mixing
// hash of (base seed, purpose, index), so that no companion of one base seed shares a Philox
// key with the base or a companion of another base seed (an additive rule, base + 7727 r, made
// repeat 1 of seed s the same run as repeat 0 of seed s + 7727).

#include <cstdint>

namespace twinflow::particle {

// SplitMix64's output function (Steele, Lea and Flood 2014): a bijection of 64-bit words whose
// outputs for nearby inputs look independent.
constexpr std::uint64_t splitmix64(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// What a derived seed is for: different purposes of one base seed never coincide.
enum class SeedPurpose : std::uint64_t { DiffusionRepeat = 1 };

// Index 0 is the base seed itself (the run already made at the state point); index r > 0 a
// hashed seed: equal to another (base', purpose', r') only by a 64-bit collision.
constexpr std::uint64_t derived_seed(std::uint64_t base, SeedPurpose purpose, std::uint64_t index) {
  if (index == 0) return base;
  return splitmix64(splitmix64(splitmix64(base) ^ static_cast<std::uint64_t>(purpose)) + index);
}

} // namespace twinflow::particle
