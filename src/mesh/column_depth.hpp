#pragma once
// Sums down the grid's columns, which several ranks may share: for each owned cell, the sum of a
// per-cell value over the cells above it in its column and half its own (a depth to the cell's centre
// when the values are thicknesses). Columns are vertical (along y), one per (x, z) cell on a mesh of
// layers. The ranks that hold the same columns (the same x range, and z range) form one
// communicator ordered from the top down, and an exclusive scan of their column totals carries the sum
// of the ranks above to each rank: O(columns) of communication, where gathering the field would be
// O(cells) on every rank.
#include <mpi.h>

#include "mesh/field.hpp"
#include "mesh/grid.hpp"

namespace granflow {

class ColumnDepth {
 public:
  explicit ColumnDepth(const Grid& grid);  // collective
  ~ColumnDepth();
  ColumnDepth(const ColumnDepth&) = delete;
  ColumnDepth& operator=(const ColumnDepth&) = delete;

  // value[k][j][i] -> sum over j' > j of value[k][j'][i] + value[k][j][i] / 2, over the owned cells of
  // the global vector (ghosts untouched). Collective.
  void to_centre_depths(Field& value) const;

 private:
  const Grid& grid_;
  MPI_Comm column_ranks_ = MPI_COMM_NULL;  // the ranks of this rank's columns, the top one first
};

}  // namespace granflow
