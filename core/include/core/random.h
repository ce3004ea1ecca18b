#pragma once
/// \file random.h
/// The project's one random stream: splitmix64 (Steele, Lea and Flood 2014), counter based, so
/// that draw k of a stream depends only on its seed and k: samples are reproducible at any
/// thread count and in any order of evaluation.

#include <cstdint>

namespace mg {

/// splitmix64's increment (the golden ratio in 64 bits).
inline constexpr std::uint64_t kSplitmixIncrement = 0x9e3779b97f4a7c15ULL;

/// splitmix64's output function: a bijective mix of the 64 bits of `x`.
constexpr std::uint64_t mix64(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// The splitmix64 value following state `x`: mix64(x + increment).
constexpr std::uint64_t splitmix64(std::uint64_t x) { return mix64(x + kSplitmixIncrement); }

/// A double uniform in [0, 1) from the top 53 bits of `bits`.
constexpr double unit_interval(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

}  // namespace mg
