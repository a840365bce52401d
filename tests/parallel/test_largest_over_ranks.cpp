// The largest of a value over the ranks, NaN on every rank if any rank's value is NaN: MPI_MAX leaves
// NaN undefined, and a NaN Courant number on one rank must reach every rank's retry of the step.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <mpi.h>

#include "mesh/gather.hpp"

namespace granflow {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

TEST(LargestOverRanks, MpiMaxIsNanOnEveryRankIfAnyRanksValueIs) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_GE(size, 2) << "run under mpirun -np 2";
  EXPECT_EQ(mpi_max(MPI_COMM_WORLD, double(rank)), double(size - 1));
  EXPECT_EQ(mpi_max(MPI_COMM_WORLD, -2.0 - rank), -2.0);
  EXPECT_TRUE(std::isnan(mpi_max(MPI_COMM_WORLD, rank == size - 1 ? nan : 1.0)));
  EXPECT_TRUE(std::isnan(mpi_max(MPI_COMM_WORLD, rank == 0 ? nan : 1e300)));
}

}  // namespace
}  // namespace granflow
