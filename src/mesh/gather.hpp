#pragma once
// Whole-domain copies of distributed fields: on rank 0 (for writers and samplers,
// io/field_sample.hpp), or on every rank (for sums along whole columns, which cross ranks); and the
// largest of a value over the ranks.
#include <vector>

#include "mesh/field.hpp"

namespace granflow {

// Owned values of `field` in natural order (index j * nx + i) on rank 0; empty on other ranks.
std::vector<double> gather_to_root(const Grid& grid, const Field& field);
// The same from a global vector of the grid's field layout.
std::vector<double> gather_to_root(const Grid& grid, Vec global);
// Every value of `field` in natural order, on every rank.
std::vector<double> gather_to_all(const Grid& grid, const Field& field);

// The largest of each rank's v, on every rank.
inline double mpi_max(MPI_Comm comm, double v) {
  double r = v;
  MPI_Allreduce(&v, &r, 1, MPI_DOUBLE, MPI_MAX, comm);
  return r;
}

}  // namespace granflow
