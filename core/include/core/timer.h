#pragma once
/// \file timer.h
/// Wall-clock time of a stage and the process's peak memory, for the programs' `--stats`.

#include <sys/resource.h>

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

/// The process's peak resident set size so far (getrusage's ru_maxrss), MB of 2^20 bytes.
inline double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

}  // namespace mg
