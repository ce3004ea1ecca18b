#include "evaluate/timing.h"

#include "core/errors.h"

#include <algorithm>
#include <chrono>
#include <string>

namespace mg::evaluate {

StageTiming time_stage(int repeats, const std::function<void()>& stage) {
  if (repeats < 1)
    throw InvalidInput("timing: repeat count must be >= 1, got " + std::to_string(repeats));
  using Clock = std::chrono::steady_clock;
  StageTiming t;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = Clock::now();
    stage();
    t.seconds.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  std::vector<double> sorted = t.seconds;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  t.min = sorted.front();
  t.max = sorted.back();
  t.median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  return t;
}

}  // namespace mg::evaluate
