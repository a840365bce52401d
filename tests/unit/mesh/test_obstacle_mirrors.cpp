// The ghost values an obstacle's blocked cells hold (mirror_into_blocked): each the mirror across its
// nearest wall, as the domain's ghosts are, so that an open cell reads behind every wall face the
// ghost of that face.
#include <gtest/gtest.h>

#include "mesh/field.hpp"
#include "mesh/grid.hpp"
#include "mesh/obstacles.hpp"

namespace granflow {
namespace {

// A barrier of columns 4-6 and rows 0-4 on 12 x 10 cells, on the floor; every cell holds
// 100 i + j, mirrored as a velocity (sign -1).
TEST(ObstacleMirrors, EachBlockedCellMirrorsAcrossItsNearestWall) {
  GridSpec spec;
  spec.cells = {12, 10, 1};
  const Grid g(PETSC_COMM_SELF, spec);
  Field mask(g), value(g);
  {
    FieldArray m(g.field_dm(), mask.global()), a(g.field_dm(), value.global());
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 12; ++i) {
        m[j][i] = i >= 4 && i <= 6 && j <= 4 ? 1.0 : 0.0;
        a[j][i] = 100.0 * i + j;
      }
  }
  mask.scatter_to_local();
  value.scatter_to_local();
  {
    FieldArray a(g.field_dm(), value.local());
    mirror_into_blocked(g, &mask, a.volume(), -1.0);
  }
  ConstFieldArray a(g.field_dm(), value.local());
  auto cell = [](int i, int j) { return 100.0 * i + j; };
  // Behind the east and west faces, one row below the top: the wall along x is one cell away, the
  // top two. The open cells beside them read their own mirror (before, the top's: -(100 i + 6)).
  EXPECT_EQ(a[3][6], -cell(7, 3));
  EXPECT_EQ(a[3][4], -cell(3, 3));
  // Under the top, between the sides: the top is nearer.
  EXPECT_EQ(a[4][5], -cell(5, 5));
  // The top corners, a wall as near along either axis: the top's, as at the domain's corners.
  EXPECT_EQ(a[4][6], -cell(6, 5));
  EXPECT_EQ(a[4][4], -cell(4, 5));
  // Two cells behind the top and two behind either side: the top's, mirroring the second cell above.
  EXPECT_EQ(a[3][5], -cell(5, 6));
  // On the floor, two cells behind either side and far below the top: the high side's, the second
  // cell beyond it.
  EXPECT_EQ(a[0][5], -cell(8, 0));
}

// A floor and walls built of two layers of blocked cells (i < 2, j < 2, and on a mesh of layers k < 2)
// around the open cells of a box: every blocked cell holds what the domain's ghosts would hold were the
// open box the whole domain with walls on those sides (mesh/side_ghosts.hpp), edges and corners
// included: the cell m layers behind a wall mirrors the cell m - 1 in front of it, across each wall it
// lies behind, the sign once per wall.
void expect_the_domains_ghosts(int layers) {
  GridSpec spec;
  spec.cells = {7, 6, layers};
  const Grid g(PETSC_COMM_SELF, spec);
  const bool three = layers > 1;
  auto blocked = [&](int i, int j, int k) { return i < 2 || j < 2 || (three && k < 2); };
  auto value = [](int i, int j, int k) { return 100.0 * i + 10.0 * j + k + 0.5; };
  Field mask(g), f(g);
  {
    FieldArray m(g.field_dm(), mask.global()), a(g.field_dm(), f.global());
    for (int k = 0; k < layers; ++k)
      for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 7; ++i) {
          m.volume()[k][j][i] = blocked(i, j, k) ? 1.0 : 0.0;
          a.volume()[k][j][i] = blocked(i, j, k) ? 0.0 : value(i, j, k);
        }
  }
  mask.scatter_to_local();
  f.scatter_to_local();
  {
    FieldArray a(g.field_dm(), f.local());
    mirror_into_blocked(g, &mask, a.volume(), -1.0);
  }
  const ConstFieldArray a(g.field_dm(), f.local());
  int edges = 0;
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 7; ++i) {
        if (!blocked(i, j, k)) continue;
        // Behind a wall the mirror of index n < 2 is 3 - n; the sign once per wall crossed.
        int walls = 0;
        auto mirror = [&](int n, bool axis_built) {
          if (!axis_built || n >= 2) return n;
          ++walls;
          return 3 - n;
        };
        const int im = mirror(i, true), jm = mirror(j, true), km = mirror(k, three);
        edges += walls > 1;
        const double expected = (walls % 2 ? -1.0 : 1.0) * value(im, jm, km);
        EXPECT_EQ(a.volume()[k][j][i], expected) << "(" << i << ", " << j << ", " << k << ")";
      }
  EXPECT_GT(edges, 0);
}

TEST(ObstacleMirrors, BlockedCellsBehindAFloorAndAWallHoldTheDomainsGhosts) { expect_the_domains_ghosts(1); }

TEST(ObstacleMirrors, BlockedCellsBehindAFloorAndTwoWallsOfLayersHoldTheDomainsGhosts) { expect_the_domains_ghosts(5); }

// Which cell mirrors which is found once for a mask laid out by mark_blocked_cells: laid out again with
// other shapes, the mask mirrors its new cells, and two masks used in turn each mirror their own.
TEST(ObstacleMirrors, AMaskLaidOutAgainMirrorsItsNewCells) {
  GridSpec spec;
  spec.cells = {10, 10, 1};  // unit square, cells of 0.1
  const Grid g(PETSC_COMM_SELF, spec);
  Field mask(g), other(g), f(g);
  auto cell = [](int i, int j) { return 100.0 * i + j; };
  // The value blocked cell (i, j) takes, mirrored as a velocity (sign -1) by `m`.
  auto mirrored = [&](const Field& m, int i, int j) {
    {
      FieldArray a(g.field_dm(), f.global());
      for (int jj = 0; jj < 10; ++jj)
        for (int ii = 0; ii < 10; ++ii) a[jj][ii] = cell(ii, jj);
    }
    f.scatter_to_local();
    FieldArray a(g.field_dm(), f.local());
    mirror_into_blocked(g, &m, a.volume(), -1.0);
    return a[j][i];
  };
  using interface::Box;
  mark_blocked_cells(g, interface::ShapeUnion({Box{{0.4, 0.0}, {0.7, 0.5}}}), mask);  // columns 4-6, rows 0-4
  mark_blocked_cells(g, interface::ShapeUnion({Box{{0.0, 0.8}, {1.0, 1.0}}}), other);  // rows 8-9
  EXPECT_EQ(mirrored(mask, 4, 3), -cell(3, 3));  // behind the west face
  EXPECT_EQ(mirrored(other, 4, 8), -cell(4, 7));  // behind the bottom face of the other
  EXPECT_EQ(mirrored(mask, 6, 3), -cell(7, 3));  // the first mask's own again
  mark_blocked_cells(g, interface::ShapeUnion({Box{{0.2, 0.0}, {0.5, 0.5}}}), mask);  // now columns 2-4
  EXPECT_EQ(mirrored(mask, 4, 3), -cell(5, 3));  // behind the new east face
  EXPECT_EQ(mirrored(mask, 2, 3), -cell(1, 3));
}

// Which obstacle a cell belongs to (mark_obstacle_index): one plus the index of the last shape that
// holds its centre, 0 in open cells and in the ghosts outside the domain.
TEST(ObstacleIndex, EachCellTakesTheLastObstacleHoldingItsCentre) {
  GridSpec spec;
  spec.cells = {10, 10, 1};  // unit square, cells of 0.1
  const Grid g(PETSC_COMM_SELF, spec);
  Field index(g);
  const interface::ShapeUnion shapes({interface::Box{{0.0, 0.0}, {0.6, 0.3}}, interface::Box{{0.4, 0.0}, {1.0, 0.5}}});
  mark_obstacle_index(g, shapes, index);
  ConstFieldArray a(g.field_dm(), index.local());
  EXPECT_EQ(a[0][0], 1.0);  // the first alone
  EXPECT_EQ(a[2][4], 2.0);  // in both: the second, listed last
  EXPECT_EQ(a[4][9], 2.0);  // the second alone
  EXPECT_EQ(a[4][2], 0.0);  // open
  EXPECT_EQ(a[0][-1], 0.0);  // ghosts beyond the sides
  EXPECT_EQ(a[-1][5], 0.0);
}

}  // namespace
}  // namespace granflow
