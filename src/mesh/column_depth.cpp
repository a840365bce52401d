#include "mesh/column_depth.hpp"

#include <vector>

namespace granflow {

ColumnDepth::ColumnDepth(const Grid& grid) : grid_(grid) {
  const CellBox& b = grid.owned();
  // Ranks of one x range (and z range, on a mesh of layers) share its columns; a higher block comes first.
  MPI_Comm_split(grid.comm(), b.xs + grid.nx() * b.zs, -b.ys, &column_ranks_);
}

ColumnDepth::~ColumnDepth() {
  if (column_ranks_ != MPI_COMM_NULL) MPI_Comm_free(&column_ranks_);
}

void ColumnDepth::to_centre_depths(Field& value) const {
  const CellBox& b = grid_.owned();
  FieldArray v(grid_.field_dm(), value.global());
  double*** a = v.volume();
  // The columns of this rank's block, x fastest: (i, k).
  const size_t columns = size_t(b.xm) * b.zm;
  auto column = [&](int i, int k) { return size_t(k - b.zs) * b.xm + (i - b.xs); };
  std::vector<double> own(columns, 0.0), above(columns, 0.0);
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) own[column(i, k)] += a[k][j][i];
  MPI_Exscan(own.data(), above.data(), int(columns), MPI_DOUBLE, MPI_SUM, column_ranks_);
  int place = 0;
  MPI_Comm_rank(column_ranks_, &place);
  if (place == 0) above.assign(columns, 0.0);  // the top ranks: nothing above (Exscan leaves it undefined)
  for (int k = b.zs; k < b.ze(); ++k)
    for (int i = b.xs; i < b.xe(); ++i) {
      double sum = above[column(i, k)];
      for (int j = b.ye() - 1; j >= b.ys; --j) {
        const double here = a[k][j][i];
        a[k][j][i] = sum + 0.5 * here;
        sum += here;
      }
    }
}

}  // namespace granflow
