#include "mesh/column_depth.hpp"

#include <vector>

namespace granflow {

ColumnDepth::ColumnDepth(const Grid& grid) : grid_(grid) {
  const CellBox& b = grid.owned();
  // Ranks of one x range share its columns; a higher block comes first.
  MPI_Comm_split(grid.comm(), b.xs, -b.ys, &column_ranks_);
}

ColumnDepth::~ColumnDepth() {
  if (column_ranks_ != MPI_COMM_NULL) MPI_Comm_free(&column_ranks_);
}

void ColumnDepth::to_centre_depths(Field& value) const {
  const CellBox& b = grid_.owned();
  FieldArray v(grid_.field_dm(), value.global());
  std::vector<double> own(size_t(b.xm), 0.0), above(size_t(b.xm), 0.0);
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) own[size_t(i - b.xs)] += v[j][i];
  MPI_Exscan(own.data(), above.data(), b.xm, MPI_DOUBLE, MPI_SUM, column_ranks_);
  int place = 0;
  MPI_Comm_rank(column_ranks_, &place);
  if (place == 0) above.assign(size_t(b.xm), 0.0);  // the top ranks: nothing above (Exscan leaves it undefined)
  for (int i = b.xs; i < b.xe(); ++i) {
    double sum = above[size_t(i - b.xs)];
    for (int j = b.ye() - 1; j >= b.ys; --j) {
      const double here = v[j][i];
      v[j][i] = sum + 0.5 * here;
      sum += here;
    }
  }
}

}  // namespace granflow
