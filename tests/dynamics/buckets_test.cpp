// Buckets (dynamics/buckets.h): a stable counting sort, checked against std::stable_sort
// on seeded random keys, some negative (left out) and some buckets empty.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "dynamics/buckets.h"

namespace polysim::dynamics {
namespace {

TEST(Buckets, HoldEachKeptItemOnceInItsKeysBucketInTheOrderItCame) {
  std::mt19937 random(17);
  for (int trial = 0; trial < 200; ++trial) {
    const int bucketCount = std::uniform_int_distribution<int>(0, 12)(random);
    const int itemCount = std::uniform_int_distribution<int>(0, 60)(random);
    std::vector<int> keys;
    for (int i = 0; i < itemCount; ++i) keys.push_back(std::uniform_int_distribution<int>(-2, bucketCount - 1)(random));
    std::vector<int> expected;  // the kept items, stably sorted by key
    for (int i = 0; i < itemCount; ++i)
      if (keys[i] >= 0) expected.push_back(i);
    std::stable_sort(expected.begin(), expected.end(), [&](int x, int y) { return keys[x] < keys[y]; });

    const Buckets buckets(bucketCount, keys);
    ASSERT_EQ(buckets.bucketCount(), bucketCount);
    EXPECT_EQ(buckets.items, expected) << "trial " << trial;
    for (int b = 0; b < bucketCount; ++b) {
      EXPECT_EQ(buckets.empty(b), buckets.begin(b) == buckets.end(b));
      for (const int* i = buckets.begin(b); i != buckets.end(b); ++i) EXPECT_EQ(keys[*i], b) << "trial " << trial << ", bucket " << b;
    }
  }
}

}  // namespace
}  // namespace polysim::dynamics
