// The small utilities every module shares: the random stream, disjoint sets, the stopwatch.
#include "core/random.h"
#include "core/timer.h"
#include "core/union_find.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

namespace {

TEST(Random, Splitmix64MatchesTheReferenceStream) {
  // The first outputs of Vigna's splitmix64.c from state 0: the published test vector.
  std::uint64_t state = 0;
  const std::uint64_t expected[] = {0xe220a8397b1dcdafULL, 0x6e789e6aa1b965f4ULL,
                                    0x06c45d188009454fULL};
  for (std::uint64_t e : expected) {
    EXPECT_EQ(mg::splitmix64(state), e);
    state += mg::kSplitmixIncrement;
  }
}

TEST(Random, UnitIntervalTakesTheTop53Bits) {
  EXPECT_EQ(mg::unit_interval(0), 0.0);
  EXPECT_EQ(mg::unit_interval(~std::uint64_t(0)), 1.0 - 0x1.0p-53);
  EXPECT_EQ(mg::unit_interval(std::uint64_t(1) << 63), 0.5);
  EXPECT_EQ(mg::unit_interval((std::uint64_t(1) << 11) - 1), 0.0);  // the low 11 bits are dropped
}

TEST(Random, CounterBasedDrawsLookUniform) {
  // 100,000 draws of a counter stream: mean 1/2 and variance 1/12 within 4 standard errors.
  const int n = 100000;
  double sum = 0, sum2 = 0;
  for (int k = 0; k < n; ++k) {
    const double u = mg::unit_interval(mg::splitmix64(12345 * mg::kSplitmixIncrement + k));
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum2 += u * u;
  }
  const double mean = sum / n, variance = sum2 / n - mean * mean;
  EXPECT_NEAR(mean, 0.5, 4 * std::sqrt(1.0 / 12 / n));
  EXPECT_NEAR(variance, 1.0 / 12, 4 * std::sqrt(1.0 / 180 / n));
}

TEST(UnionFind, ClassesAreRepresentedByTheirSmallestElement) {
  mg::UnionFind sets(8);
  sets.unite(5, 3);
  sets.unite(7, 5);
  sets.unite(6, 1);
  EXPECT_EQ(sets.find(7), 3u);
  EXPECT_EQ(sets.find(5), 3u);
  EXPECT_EQ(sets.find(6), 1u);
  EXPECT_EQ(sets.find(0), 0u);
  sets.unite(6, 7);  // joins {1, 6} and {3, 5, 7}
  for (std::size_t i : {1u, 3u, 5u, 6u, 7u}) EXPECT_EQ(sets.find(i), 1u) << i;
  EXPECT_EQ(sets.find(2), 2u);
}

TEST(UnionFind, TheOrderOfTheUnionsDoesNotMatter) {
  const std::vector<std::pair<int, int>> pairs = {{9, 4}, {2, 8}, {4, 2}, {11, 10}, {0, 6}};
  mg::UnionFind forward(12), backward(12);
  for (const auto& [a, b] : pairs) forward.unite(a, b);
  for (auto it = pairs.rbegin(); it != pairs.rend(); ++it) backward.unite(it->second, it->first);
  for (std::size_t i = 0; i < 12; ++i) EXPECT_EQ(forward.find(i), backward.find(i)) << i;
}

TEST(Stopwatch, MeasuresAtLeastTheTimeSleptAndRestarts) {
  const mg::Stopwatch total;
  mg::Stopwatch clock;
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_GE(clock.restart(), 0.005);
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const double since_restart = clock.seconds();
  EXPECT_GE(since_restart, 0.005);
  EXPECT_LE(since_restart + 0.005, total.seconds());  // the restart dropped the first sleep
}

}  // namespace
