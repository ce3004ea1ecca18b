#pragma once
/// \file timer.h
/// Wall-clock time of a stage, for the programs' `--stats` (steady clock, seconds).

#include <chrono>

namespace mg {

/// Starts at construction; seconds() is the time since then (or since the last restart()).
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  /// Returns seconds() and starts again.
  double restart() {
    const double s = seconds();
    start_ = std::chrono::steady_clock::now();
    return s;
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace mg
