#pragma once
// Whole-domain copies of distributed fields: on rank 0 (for writers and samplers,
// io/field_sample.hpp), or on every rank (for sums along whole columns, which cross ranks); and the
// largest of a value over the ranks.
#include <cmath>
#include <limits>
#include <vector>

#include "mesh/field.hpp"

namespace granflow {

// Owned values of `field` in natural order (index j * nx + i) on rank 0; empty on other ranks.
std::vector<double> gather_to_root(const Grid& grid, const Field& field);
// Every value of `field` in natural order, on every rank.
std::vector<double> gather_to_all(const Grid& grid, const Field& field);

// The largest of each rank's v, on every rank; NaN on every rank if any rank's v is NaN (MPI_MAX
// leaves NaN undefined, and a NaN Courant number must reach the step's retry).
inline double mpi_max(MPI_Comm comm, double v) {
  const double mine[2] = {std::isnan(v) ? 1.0 : 0.0, std::isnan(v) ? -HUGE_VAL : v};
  double all[2];
  MPI_Allreduce(mine, all, 2, MPI_DOUBLE, MPI_MAX, comm);
  return all[0] > 0.0 ? std::numeric_limits<double>::quiet_NaN() : all[1];
}

// The largest |value| of a distributed vector on every rank; NaN on every rank if any value is NaN.
// In place of VecNorm(NORM_INFINITY), which reduces with a plain MPI_MAX: a NaN on one rank may be
// lost there, and a diverged velocity must reach the divergence check.
double max_abs(MPI_Comm comm, Vec v);

}  // namespace granflow
