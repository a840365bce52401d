// A grid's ranks: a planar mesh is laid out as PETSc lays out a 2D DMDA, a mesh of several layers
// is split where the ranks share the least area, and the ghost exchange fills every neighbour of
// an owned cell in 3D.
#include <gtest/gtest.h>

#include <mpi.h>

#include <algorithm>

#include "mesh/copied_ghosts.hpp"
#include "mesh/field.hpp"
#include "mesh/grid.hpp"

namespace granflow {
namespace {

int ranks() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

TEST(GridLayers, APlanarMeshIsLaidOutAsA2dDmda) {
  ASSERT_GE(ranks(), 2) << "run under mpirun -np 2";
  for (const auto& cells : {std::array<int, 3>{30, 10, 1}, {10, 30, 1}, {12, 12, 1}}) {
    GridSpec spec;
    spec.cells = cells;
    const Grid g(MPI_COMM_WORLD, spec);
    DM plane;
    PetscCallAbort(MPI_COMM_WORLD, DMDACreate2d(MPI_COMM_WORLD, DM_BOUNDARY_GHOSTED, DM_BOUNDARY_GHOSTED,
                                                DMDA_STENCIL_BOX, cells[0], cells[1], PETSC_DECIDE, PETSC_DECIDE, 1,
                                                Grid::ghost_width, nullptr, nullptr, &plane));
    PetscCallAbort(MPI_COMM_WORLD, DMSetUp(plane));
    PetscInt xs, ys, xm, ym;
    PetscCallAbort(MPI_COMM_WORLD, DMDAGetCorners(plane, &xs, &ys, nullptr, &xm, &ym, nullptr));
    PetscCallAbort(MPI_COMM_WORLD, DMDestroy(&plane));
    const CellBox& b = g.owned();
    EXPECT_EQ(b.xs, xs);
    EXPECT_EQ(b.ys, ys);
    EXPECT_EQ(b.xm, xm);
    EXPECT_EQ(b.ym, ym);
    EXPECT_EQ(b.zm, 1);
  }
}

TEST(GridLayers, SeveralLayersAreSplitAcrossTheSmallestAreaAndTheirGhostsExchanged) {
  ASSERT_EQ(ranks(), 2) << "run under mpirun -np 2";
  GridSpec spec;
  spec.cells = {6, 5, 8};  // cuts across x, y, z share 40, 48 and 30 faces: z is cut
  spec.upper = {0.6, 0.5, 0.8};
  const Grid g(MPI_COMM_WORLD, spec);
  const CellBox& b = g.owned();
  EXPECT_EQ(b.xm, 6);
  EXPECT_EQ(b.ym, 5);
  EXPECT_EQ(b.zm, 4);
  auto value = [](int i, int j, int k) { return i + 10.0 * j + 100.0 * k; };
  Field f(g);
  {
    FieldArray a(g.field_dm(), f.global());
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) a.volume()[k][j][i] = value(i, j, k);
  }
  f.scatter_to_local();
  ConstFieldArray a = local_read(g, f);
  int checked = 0;
  for (int k = b.zs - 2; k < b.ze() + 2; ++k)
    for (int j = b.ys - 2; j < b.ye() + 2; ++j)
      for (int i = b.xs - 2; i < b.xe() + 2; ++i)
        if (!g.outside(i, j, k)) {
          EXPECT_EQ(a.volume()[k][j][i], value(i, j, k)) << "cell " << i << ", " << j << ", " << k;
          ++checked;
        }
  EXPECT_EQ(checked, 6 * 5 * 6) << "four owned layers and two of the other rank's";
  // Copied ghosts: the other rank's layers where it has them, the nearest cell beyond the box.
  fill_copied_ghosts(g, nullptr, f);
  ConstFieldArray c = local_read(g, f);
  for (int k = b.zs - 2; k < b.ze() + 2; ++k)
    for (int j = -2; j < 7; ++j)
      for (int i = -2; i < 8; ++i)
        EXPECT_EQ(c.volume()[k][j][i], value(std::clamp(i, 0, 5), std::clamp(j, 0, 4), std::clamp(k, 0, 7)))
            << "cell " << i << ", " << j << ", " << k;
}

TEST(GridLayers, TooManyRanksForSeveralLayersIsAGridError) {
  ASSERT_GE(ranks(), 2) << "run under mpirun -np 2";
  GridSpec spec;
  spec.cells = {3, 3, 3};  // no axis holds two ranks of two cells each
  try {
    const Grid g(MPI_COMM_WORLD, spec);
    FAIL() << "laid out";
  } catch (const GridError& e) {
    EXPECT_STREQ(e.what(), "mesh.cells: 3 x 3 x 3 cells cannot be shared by 2 ranks (each needs at least 2 cells along "
                           "each axis it is split along); use fewer ranks or more cells");
  }
}

}  // namespace
}  // namespace granflow
