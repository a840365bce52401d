// A grid's third axis: a mesh of one layer along z is planar (a metre deep, no ghosts along z), one of
// several is three-dimensional, with graded layers and two ghost layers beyond its z sides.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "mesh/copied_ghosts.hpp"
#include "mesh/face_loop.hpp"
#include "mesh/field.hpp"
#include "mesh/grid.hpp"

namespace granflow {
namespace {

TEST(GridLayers, OneLayerIsAPlanarMeshAMetreDeepWithoutGhostsAlongZ) {
  GridSpec spec;
  spec.cells = {6, 4, 1};
  spec.upper = {0.6, 0.4};  // z entries left unset: a planar mesh does not read them
  const Grid g(PETSC_COMM_SELF, spec);
  EXPECT_EQ(g.dimension(), 2);
  EXPECT_EQ(g.cell_count(), 24);
  EXPECT_EQ(g.dz(0), 1.0);
  EXPECT_EQ(g.zc(0), 0.5);
  EXPECT_EQ(g.owned().zs, 0);
  EXPECT_EQ(g.owned().zm, 1);
  PetscInt gzs, gzm;
  PetscCallAbort(PETSC_COMM_SELF, DMDAGetGhostCorners(g.field_dm(), nullptr, nullptr, &gzs, nullptr, nullptr, &gzm));
  EXPECT_EQ(gzs, 0);
  EXPECT_EQ(gzm, 1);
  // The plane view and the volume view are the same storage.
  Field f(g);
  FieldArray a = local_array(g, f);
  a[-2][-2] = 3.0;
  a[3][5] = 7.0;
  EXPECT_EQ(a.volume()[0][-2][-2], 3.0);
  EXPECT_EQ(a.volume()[0][3][5], 7.0);
}

TEST(GridLayers, SeveralLayersAreGradedCellsFillingTheBox) {
  GridSpec spec;
  spec.cells = {3, 4, 5};
  spec.lower = {0.0, -1.0, 2.0};
  spec.upper = {0.3, 1.0, 3.0};
  spec.grading = {1.0, 1.0, 4.0};
  const Grid g(PETSC_COMM_SELF, spec);
  EXPECT_EQ(g.dimension(), 3);
  EXPECT_EQ(g.cell_count(), 60);
  double depth = 0.0, volume = 0.0;
  for (int k = 0; k < 5; ++k) depth += g.dz(k);
  EXPECT_NEAR(depth, 1.0, 1e-14);
  EXPECT_NEAR(g.dz(4) / g.dz(0), 4.0, 1e-12);
  EXPECT_NEAR(g.zf(4), 3.0, 1e-14);
  EXPECT_NEAR(g.zc(0) - 0.5 * g.dz(0), 2.0, 1e-14);
  EXPECT_NEAR(g.zc(-1), 2.0 - (g.zc(0) - 2.0), 1e-14) << "ghost centres mirror the first layer's";
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 3; ++i) volume += g.volume(i, j, k);
  EXPECT_NEAR(volume, 0.3 * 2.0 * 1.0, 1e-14);
  EXPECT_DOUBLE_EQ(g.face_area(0, 1, 2, 3, 1.0), g.dy(2) * g.dz(3));
  EXPECT_DOUBLE_EQ(g.face_area(1, 1, 2, 3, 1.0), g.dx(1) * g.dz(3));
  EXPECT_DOUBLE_EQ(g.face_area(2, 1, 2, 3, 1.0), g.dx(1) * g.dy(2));
  EXPECT_NEAR(g.min_spacing(), g.dz(0), 1e-15);  // the first layer, 0.2 / 2.5 of a mean one
  EXPECT_TRUE(g.outside(0, 0, -1));
  EXPECT_TRUE(g.outside(0, 0, 5));
  EXPECT_FALSE(g.outside(2, 3, 4));
  PetscInt gzs, gzm;
  PetscCallAbort(PETSC_COMM_SELF, DMDAGetGhostCorners(g.field_dm(), nullptr, nullptr, &gzs, nullptr, nullptr, &gzm));
  EXPECT_EQ(gzs, -Grid::ghost_width);
  EXPECT_EQ(gzm, 5 + 2 * Grid::ghost_width);
}

TEST(GridLayers, ARefusedSpecSaysWhy) {
  GridSpec spec;
  spec.cells = {3, 4, 0};
  EXPECT_THROW(Grid(PETSC_COMM_SELF, spec), std::invalid_argument);
  spec.cells = {3, 4, 2};
  spec.upper = {1.0, 1.0, 0.0};  // no depth
  EXPECT_THROW(Grid(PETSC_COMM_SELF, spec), std::invalid_argument);
  spec.upper = {1.0, 1.0, 1.0};
  spec.axisymmetric = true;
  EXPECT_THROW(Grid(PETSC_COMM_SELF, spec), std::invalid_argument);
}

TEST(GridLayers, SidesAlongZAreBoundariesOfLayersOnly) {
  GridSpec spec;
  spec.cells = {3, 4, 1};
  const Grid planar(PETSC_COMM_SELF, spec);
  EXPECT_FALSE(planar.bounded(Side::front));
  EXPECT_FALSE(planar.owns_boundary(Side::back));
  EXPECT_EQ(sides_of_dimension(planar.dimension()).size(), 4u);
  spec.cells = {3, 4, 2};
  const Grid layers(PETSC_COMM_SELF, spec);
  EXPECT_TRUE(layers.owns_boundary(Side::front));
  EXPECT_TRUE(layers.owns_boundary(Side::back));
  EXPECT_EQ(sides_of_dimension(layers.dimension()).size(), 6u);
  for (Side s : box_sides) {
    EXPECT_EQ(side_of(normal_axis(s), int(outward_normal(s, normal_axis(s)))), s) << side_name(s);
    for (int axis = 0; axis < 3; ++axis)
      if (axis != normal_axis(s)) EXPECT_EQ(outward_normal(s, axis), 0.0);
  }
  EXPECT_STREQ(side_name(Side::front), "front");
  EXPECT_EQ(outward_normal(Side::back, 2), 1.0);
}

// Each ghost of a copied field, beyond a face, an edge or a corner of the box, is its nearest cell's value.
TEST(GridLayers, CopiedGhostsAreTheNearestCellsBeyondFacesEdgesAndCorners) {
  GridSpec spec;
  spec.cells = {4, 3, 5};
  const Grid g(PETSC_COMM_SELF, spec);
  Field f(g);
  auto value = [](int i, int j, int k) { return i + 10.0 * j + 100.0 * k; };
  {
    FieldArray a(g.field_dm(), f.global());
    for (int k = 0; k < 5; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 4; ++i) a.volume()[k][j][i] = value(i, j, k);
  }
  fill_copied_ghosts(g, nullptr, f);
  ConstFieldArray a = local_read(g, f);
  const int w = Grid::ghost_width;
  for (int k = -w; k < 5 + w; ++k)
    for (int j = -w; j < 3 + w; ++j)
      for (int i = -w; i < 4 + w; ++i)
        EXPECT_EQ(a.volume()[k][j][i], value(std::clamp(i, 0, 3), std::clamp(j, 0, 2), std::clamp(k, 0, 4)))
            << i << ", " << j << ", " << k;
}

// Every face of every cell once, in the layout of the face fields: interior faces from both cells'
// indices, boundary faces from their one cell and side.
TEST(GridLayers, TheFaceLoopVisitsEachFaceOfTheCellsOnce) {
  GridSpec spec;
  spec.cells = {3, 4, 5};
  const Grid g(PETSC_COMM_SELF, spec);
  Field fx(g), fy(g), fz(g);
  for (Field* f : {&fx, &fy, &fz}) {
    f->set(-1.0);  // unvisited
  }
  const int n[3] = {3, 4, 5};
  int boundary_faces = 0, interior_faces = 0;
  fill_owned_faces_3d(
      g, {&fx, &fy, &fz},
      [&](int axis, int i, int j, int k) {
        ++interior_faces;
        return 1000.0 * axis + i + 10.0 * j + 100.0 * k;  // the low cell's index
      },
      [&](int axis, int i, int j, int k, int sign) {
        ++boundary_faces;
        const int along = axis == 0 ? i : (axis == 1 ? j : k);
        EXPECT_EQ(along, sign < 0 ? 0 : n[axis] - 1) << "a boundary face's cell lies on its side";
        return -10.0 - sign;
      });
  EXPECT_EQ(boundary_faces, 2 * (4 * 5 + 3 * 5 + 3 * 4));
  EXPECT_EQ(interior_faces, 2 * 4 * 5 + 3 * 3 * 5 + 3 * 4 * 4);
  ConstFieldArray a[3] = {local_read(g, fx), local_read(g, fy), local_read(g, fz)};
  for (int axis = 0; axis < 3; ++axis)
    for (int k = axis == 2 ? -1 : 0; k < 5; ++k)
      for (int j = axis == 1 ? -1 : 0; j < 4; ++j)
        for (int i = axis == 0 ? -1 : 0; i < 3; ++i) {
          const int along = axis == 0 ? i : (axis == 1 ? j : k);
          const double expected = along < 0 ? -9.0 : (along + 1 == n[axis] ? -11.0 : 1000.0 * axis + i + 10.0 * j + 100.0 * k);
          EXPECT_EQ(a[axis].volume()[k][j][i], expected) << axis << ": " << i << ", " << j << ", " << k;
        }
}

}  // namespace
}  // namespace granflow
