// The velocity's ghosts beyond the sides of a mesh of layers: each side's rule (inlet, moving wall, slip
// wall, atmosphere) on each component, two layers deep, and at an edge the rule of the later side applied to
// the earlier side's ghosts.
#include <gtest/gtest.h>

#include <array>

#include "mesh/field.hpp"
#include "mesh/grid.hpp"
#include "solver/velocity_ghosts.hpp"

namespace granflow {
namespace {

TEST(VelocityGhosts, EachSidesRuleOnEachComponentOfAMeshOfLayers) {
  GridSpec spec;
  spec.cells = {4, 5, 6};
  const Grid g(PETSC_COMM_SELF, spec);
  BoundarySet sides;
  sides[int(Side::west)] = {BoundaryKind::inlet, {0.4, 0.3, -0.2}};
  sides[int(Side::east)].kind = BoundaryKind::slip;
  sides[int(Side::south)].kind = BoundaryKind::wall;
  sides[int(Side::north)].kind = BoundaryKind::atmosphere;
  sides[int(Side::front)].kind = BoundaryKind::slip;
  sides[int(Side::back)] = {BoundaryKind::wall, {0.5, 0.0, 0.0}};
  Field u(g), v(g), w(g);
  auto value = [](int c, int i, int j, int k) { return 1.0 + c + 0.1 * i + 0.01 * j + 0.001 * k; };
  {
    FieldArray a[3] = {local_array(g, u), local_array(g, v), local_array(g, w)};
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 6; ++k)
        for (int j = 0; j < 5; ++j)
          for (int i = 0; i < 4; ++i) a[c].volume()[k][j][i] = value(c, i, j, k);
    double*** const components[3] = {a[0].volume(), a[1].volume(), a[2].volume()};
    fill_velocity_side_ghosts(g, sides, components);
  }
  ConstFieldArray a[3] = {local_read(g, u), local_read(g, v), local_read(g, w)};
  auto at = [&](int c, int i, int j, int k) { return a[c].volume()[k][j][i]; };
  for (int c = 0; c < 3; ++c)
    for (int m = 1; m <= 2; ++m) {
      // West, an inlet at (0.4, 0.3, -0.2): the face between ghost and mirror cell at its velocity.
      EXPECT_DOUBLE_EQ(at(c, -m, 2, 3), 2.0 * sides[0].velocity[c] - value(c, m - 1, 2, 3));
      // East, slip: the normal component turned, the others as they are.
      EXPECT_DOUBLE_EQ(at(c, 3 + m, 2, 3), (c == 0 ? -1.0 : 1.0) * value(c, 4 - m, 2, 3));
      EXPECT_DOUBLE_EQ(at(c, 1, -m, 3), -value(c, 1, m - 1, 3));  // south, a wall at rest
      EXPECT_DOUBLE_EQ(at(c, 1, 4 + m, 3), value(c, 1, 4, 3));  // north, atmosphere: zero gradient
      EXPECT_DOUBLE_EQ(at(c, 1, 2, -m), (c == 2 ? -1.0 : 1.0) * value(c, 1, 2, m - 1));  // front, slip
      EXPECT_DOUBLE_EQ(at(c, 1, 2, 5 + m), 2.0 * sides[5].velocity[c] - value(c, 1, 2, 6 - m));  // back
    }
  // The edge between the west inlet and the back wall: the back's rule on the west's ghosts.
  EXPECT_DOUBLE_EQ(at(1, -1, 2, 6), 2.0 * 0.0 - at(1, -1, 2, 5));
  EXPECT_DOUBLE_EQ(at(1, -1, 2, 5), 2.0 * 0.3 - value(1, 0, 2, 5));
}

}  // namespace
}  // namespace granflow
