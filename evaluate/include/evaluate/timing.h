#pragma once
/// \file timing.h
/// Wall-clock timing of a stage run several times (Table 2 style: report min, median, max).

#include <functional>
#include <vector>

namespace mg::evaluate {

struct StageTiming {
  std::vector<double> seconds;  ///< every run, in order
  double min = 0, median = 0,
         max = 0;  ///< seconds; median of an even count = mean of the two middle runs
};

/// Runs `stage` `repeats` times back to back and times each run (steady clock).
/// @pre repeats >= 1   @throws InvalidInput; whatever `stage` throws (on its first failure)
StageTiming time_stage(int repeats, const std::function<void()>& stage);

}  // namespace mg::evaluate
