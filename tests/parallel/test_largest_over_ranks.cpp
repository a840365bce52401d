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

// The largest |value| of a distributed vector (the velocity the divergence check and the outer
// iterations' convergence read): NaN on every rank wherever the NaN lies, the largest magnitude
// otherwise, a negative value's included.
TEST(LargestOverRanks, MaxAbsOfAVectorIsNanOnEveryRankIfAnyValueIs) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_GE(size, 2) << "run under mpirun -np 2";
  Vec v;
  ASSERT_EQ(VecCreateMPI(MPI_COMM_WORLD, 3, PETSC_DECIDE, &v), 0);
  auto fill = [&](int nan_rank) {
    PetscScalar* a;
    VecGetArray(v, &a);
    for (int k = 0; k < 3; ++k) a[k] = rank == size - 1 && k == 1 ? -7.0 : 1.0 + k;
    if (rank == nan_rank) a[2] = nan;
    VecRestoreArray(v, &a);
  };
  fill(-1);
  EXPECT_EQ(max_abs(MPI_COMM_WORLD, v), 7.0);
  for (int nan_rank = 0; nan_rank < size; ++nan_rank) {
    fill(nan_rank);
    EXPECT_TRUE(std::isnan(max_abs(MPI_COMM_WORLD, v))) << "NaN on rank " << nan_rank;
  }
  VecDestroy(&v);
}

}  // namespace
}  // namespace granflow
