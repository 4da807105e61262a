// The step search of `drapelab stability` on its own (runner/step_search.hpp), with a synthetic
// stability rule whose answer is known.
#include <gtest/gtest.h>

#include <functional>
#include <optional>
#include <set>
#include <vector>

#include "drapelab/runner/step_search.hpp"

namespace {

// The search alone, with a rule whose answer is known: stable iff k >= threshold.
struct SyntheticRule {
  int threshold = 0;
  std::vector<int> tried;
  std::optional<bool> operator()(int k) {
    tried.push_back(k);
    return k >= threshold;
  }
};

TEST(StepSearch, BisectsToNeighbouringStepsPerFrame) {
  for (const int start : {1, 5, 100, 1000}) {
    for (const int threshold : {1, 2, 37, 47, 48, 640}) {
      SyntheticRule rule{threshold, {}};
      drapelab::runner::StepSearchLimits limits;
      limits.tolerance = 0.0;
      const auto outcome =
          drapelab::runner::search_largest_stable_step(start, limits, std::ref(rule));
      ASSERT_TRUE(outcome.stable_k);
      EXPECT_EQ(*outcome.stable_k, threshold) << "start " << start;
      if (threshold > 1) {
        ASSERT_TRUE(outcome.unstable_k);
        EXPECT_EQ(*outcome.unstable_k, threshold - 1);
      } else {
        EXPECT_FALSE(
            outcome.unstable_k);  // k = 1 (one step per frame) is the largest step there is
      }
      std::set<int> distinct(rule.tried.begin(), rule.tried.end());
      EXPECT_EQ(distinct.size(), rule.tried.size()) << "a k was tried twice";
      EXPECT_EQ(rule.tried.front(), start);
    }
  }
}

TEST(StepSearch, ToleranceStopsEarlyAndLimitsBoundTheSteps) {
  SyntheticRule rule{640, {}};
  drapelab::runner::StepSearchLimits limits;
  limits.tolerance = 0.05;
  const auto loose = drapelab::runner::search_largest_stable_step(100, limits, std::ref(rule));
  ASSERT_TRUE(loose.stable_k && loose.unstable_k);
  EXPECT_GE(*loose.stable_k, 640);
  EXPECT_LT(*loose.unstable_k, 640);
  EXPECT_LE(static_cast<double>(*loose.stable_k) / *loose.unstable_k - 1.0, 0.05);
  EXPECT_GT(*loose.stable_k - *loose.unstable_k, 1);  // stopped before neighbours

  // Nothing stable up to the largest k: no stable step, and nothing beyond the limit was tried.
  SyntheticRule never{2000000, {}};
  limits.largest_k = 1000000;
  const auto none = drapelab::runner::search_largest_stable_step(100, limits, std::ref(never));
  EXPECT_FALSE(none.stable_k);
  EXPECT_EQ(none.unstable_k, 1000000);
  for (const int k : never.tried) EXPECT_LE(k, 1000000);

  // Everything stable: the search stops at the smallest k allowed (the largest step, --max-dt).
  SyntheticRule always{1, {}};
  limits.smallest_k = 6;
  const auto capped = drapelab::runner::search_largest_stable_step(100, limits, std::ref(always));
  EXPECT_EQ(capped.stable_k, 6);
  EXPECT_FALSE(capped.unstable_k);
  for (const int k : always.tried) EXPECT_GE(k, 6);
}

TEST(StepSearch, AnInterruptedTrialStopsTheSearch) {
  int calls = 0;
  const auto outcome =
      drapelab::runner::search_largest_stable_step(100, {}, [&calls](int) -> std::optional<bool> {
        return ++calls < 3 ? std::optional<bool>(true) : std::nullopt;
      });
  EXPECT_TRUE(outcome.stopped);
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(outcome.stable_k, 50);
}

}  // namespace
