// Sums down the columns of a grid whose columns several ranks share (ColumnDepth): each cell's value
// becomes the sum of the values above it in its column plus half its own, as one rank computes it.
#include <gtest/gtest.h>

#include <mpi.h>

#include <array>

#include "mesh/column_depth.hpp"
#include "mesh/field.hpp"
#include "mesh/gather.hpp"
#include "mesh/grid.hpp"

namespace granflow {
namespace {

TEST(ColumnDepth, SumsAboveEachCentreAcrossTheRanksOfItsColumn) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_GE(size, 2) << "run under mpirun -np 2";
  GridSpec spec;
  spec.cells = {3, 40, 1};  // tall: the ranks share the columns
  const Grid grid(MPI_COMM_WORLD, spec);
  ASSERT_LT(grid.owned().ym, 40) << "the ranks do not share the columns";
  Field value(grid);
  auto of = [](int i, int j) { return 1.0 + 0.5 * i + 0.01 * j * j; };
  {
    FieldArray v(grid.field_dm(), value.global());
    const CellBox& b = grid.owned();
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) v[j][i] = of(i, j);
  }
  ColumnDepth(grid).to_centre_depths(value);
  const auto all = gather_to_all(grid, value);
  for (int i = 0; i < 3; ++i) {
    double above = 0.0;
    for (int j = 39; j >= 0; --j) {
      EXPECT_NEAR(all[size_t(j) * 3 + i], above + 0.5 * of(i, j), 1e-12 * (above + 1.0)) << "cell " << i << ", " << j;
      above += of(i, j);
    }
  }
}

// On a mesh of layers each (x, z) cell has its column; the ranks that share them are those of one x
// and z range. Split across y, two ranks share every column; split across z, each holds its own
// columns, and no rank's sums may reach another's layers.
TEST(ColumnDepth, SumsDownTheColumnsOfEveryLayer) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_EQ(size, 2) << "run under mpirun -np 2";
  for (const std::array<int, 3> cells : {std::array<int, 3>{3, 40, 4}, {4, 6, 40}}) {
    GridSpec spec;
    spec.cells = cells;
    const Grid grid(MPI_COMM_WORLD, spec);
    const bool split_along_y = cells[1] == 40;
    ASSERT_EQ(grid.owned().ym < cells[1], split_along_y);
    ASSERT_EQ(grid.owned().zm < cells[2], !split_along_y);
    Field value(grid);
    auto of = [](int i, int j, int k) { return 1.0 + 0.5 * i + 0.01 * j * j + 0.3 * k; };
    {
      FieldArray v(grid.field_dm(), value.global());
      const CellBox& b = grid.owned();
      for (int k = b.zs; k < b.ze(); ++k)
        for (int j = b.ys; j < b.ye(); ++j)
          for (int i = b.xs; i < b.xe(); ++i) v.volume()[k][j][i] = of(i, j, k);
    }
    ColumnDepth(grid).to_centre_depths(value);
    const auto all = gather_to_all(grid, value);
    for (int k = 0; k < cells[2]; ++k)
      for (int i = 0; i < cells[0]; ++i) {
        double above = 0.0;
        for (int j = cells[1] - 1; j >= 0; --j) {
          EXPECT_NEAR(all[(size_t(k) * cells[1] + j) * cells[0] + i], above + 0.5 * of(i, j, k), 1e-12 * (above + 1.0))
              << "cell " << i << ", " << j << ", " << k;
          above += of(i, j, k);
        }
      }
  }
}

}  // namespace
}  // namespace granflow
