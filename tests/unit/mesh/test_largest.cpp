// Maxima in which a NaN wins: a NaN Courant number must reach the step's retry, where std::max and
// MPI_MAX would pass over it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <mpi.h>

#include "mesh/gather.hpp"
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

TEST(Largest, MpiMaxIsNanOnEveryRankIfAnyRanksValueIs) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  EXPECT_EQ(mpi_max(MPI_COMM_WORLD, double(rank)), double(size - 1));
  EXPECT_EQ(mpi_max(MPI_COMM_WORLD, -2.0 - rank), -2.0);
  EXPECT_TRUE(std::isnan(mpi_max(MPI_COMM_WORLD, rank == size - 1 ? nan : 1.0)));
  EXPECT_TRUE(std::isnan(mpi_max(MPI_COMM_WORLD, rank == 0 ? nan : 1e300)));
}

}  // namespace
}  // namespace granflow
