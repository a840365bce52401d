// A maximum in which a NaN wins: a NaN Courant number must reach the step's retry, where std::max
// would pass over it (mpi_max over the ranks: tests/parallel/test_largest_over_ranks.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mesh/largest.hpp"

namespace granflow {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

TEST(Largest, LargerOrNanIsTheLargerOrNan) {
  EXPECT_EQ(larger_or_nan(1.0, 2.0), 2.0);
  EXPECT_EQ(larger_or_nan(2.0, 1.0), 2.0);
  EXPECT_EQ(larger_or_nan(-1.0, -HUGE_VAL), -1.0);
  EXPECT_TRUE(std::isnan(larger_or_nan(1.0, nan)));
  EXPECT_TRUE(std::isnan(larger_or_nan(nan, 1.0)));
  double running = 0.0;
  for (double v : {0.3, nan, 0.9}) running = larger_or_nan(running, v);
  EXPECT_TRUE(std::isnan(running));  // a later, larger value does not hide it
}

// The search for the fastest cell: a NaN takes the lead and keeps it, so the divergence message
// names where the NaN is, not the last cell searched.
TEST(Largest, TheFirstNanKeepsTheLead) {
  const double speeds[] = {0.5, 2.0, nan, 3.0, 0.0, nan};
  int lead = -1;
  double running = 0.0;
  for (int k = 0; k < 6; ++k)
    if (takes_the_lead(speeds[k], running)) {
      running = speeds[k];
      lead = k;
    }
  EXPECT_EQ(lead, 2);
  EXPECT_TRUE(takes_the_lead(2.0, 1.0));
  EXPECT_FALSE(takes_the_lead(1.0, 1.0));
  EXPECT_FALSE(takes_the_lead(0.5, 1.0));
}

}  // namespace
}  // namespace granflow
