// Initial soil shapes in 3D: the volume their fractions lay on a mesh against the shapes' own, for
// spheres, vertical cylinders, extruded 2D shapes, boxes and a union; and shapes smaller than a cell.
#include "models/interface/initial_shapes_3d.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace granflow::interface {
namespace {

using std::numbers::pi;

// The volume the union's fractions lay on n^3 cubic cells of [0, 1]^3.
double laid_volume(const ShapeUnion3& u, int n) {
  const double h = 1.0 / n;
  double v = 0.0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) v += u.fraction({i * h, j * h, k * h}, {(i + 1) * h, (j + 1) * h, (k + 1) * h});
  return v * h * h * h;
}

TEST(InitialShapes3d, FractionsLayEachShapesVolume) {
  const double r = 0.3;
  EXPECT_NEAR(laid_volume(ShapeUnion3({Sphere{{0.5, 0.45, 0.52}, r}}), 20), 4.0 / 3.0 * pi * r * r * r, 2e-4);
  // A granular column standing on the floor, and a block of a 2D case across a channel.
  EXPECT_NEAR(laid_volume(ShapeUnion3({VerticalCylinder{{0.4, 0.55}, 0.2, 0.0, 0.35}}), 20), pi * 0.2 * 0.2 * 0.35, 2e-4);
  EXPECT_NEAR(laid_volume(ShapeUnion3({Extrusion{Circle{{0.5, 0.5}, 0.25}, 0.1, 0.9}}), 20), pi * 0.25 * 0.25 * 0.8,
              2e-4);
  EXPECT_NEAR(laid_volume(ShapeUnion3({Extrusion{Polygon{{{0.0, 0.0}, {0.6, 0.0}, {0.0, 0.3}}}, 0.0, 1.0}}), 20),
              0.5 * 0.6 * 0.3, 2e-4);
  // A box on the cells' faces is laid exactly; one off them to the sampling: half a sample's width (h / 32)
  // times the area of its faces off the cells' faces (x = 0.13, y = 0.31), 1.5e-3 at most (3.7e-4 here).
  EXPECT_NEAR(laid_volume(ShapeUnion3({Box3{{0.1, 0.0, 0.2}, {0.5, 0.3, 0.9}}}), 10), 0.4 * 0.3 * 0.7, 1e-15);
  EXPECT_NEAR(laid_volume(ShapeUnion3({Box3{{0.13, 0.0, 0.2}, {0.5, 0.31, 0.9}}}), 10), 0.37 * 0.31 * 0.7, 1.5e-3);
}

TEST(InitialShapes3d, AUnionCountsTheOverlapOnce) {
  const ShapeUnion3 u({Box3{{0.2, 0.2, 0.2}, {0.8, 0.8, 0.8}}, Sphere{{0.5, 0.5, 0.5}, 0.25}});
  EXPECT_NEAR(laid_volume(u, 10), 0.6 * 0.6 * 0.6, 1e-15);
  EXPECT_TRUE(u.contains(0.5, 0.5, 0.5));
  EXPECT_FALSE(u.contains(0.1, 0.5, 0.5));
  EXPECT_EQ(u.size(), 2u);
}

TEST(InitialShapes3d, AShapeSmallerThanTheCellIsSampledEvenBetweenItsProbes) {
  // A sphere that holds neither the cell's centre nor a corner.
  const ShapeUnion3 u({Sphere{{0.25, 0.3, 0.7}, 0.1}});
  EXPECT_NEAR(u.fraction({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, 64), 4.0 / 3.0 * pi * 1e-3, 1e-4);
  // A slot narrower than a fifth of the cell cut into an extruded section off the cell's centre: all
  // nine probes lie in the soil, and only the section's outline shows the slot.
  const ShapeUnion3 slot({Extrusion{Polygon{{{-1.0, -1.0}, {2.0, -1.0}, {2.0, 2.0}, {0.7, 2.0}, {0.7, 0.3}, {0.65, 0.3},
                                             {0.65, 2.0}, {-1.0, 2.0}}},
                                    -1.0, 2.0}});
  EXPECT_NEAR(slot.fraction({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, 64), 1.0 - 0.05 * 0.7, 1.2e-2);  // 3 x 45 of 64^2 samples
}

TEST(InitialShapes3d, BoundingBoxes) {
  const auto [lo, hi] = bounding_box(VerticalCylinder{{0.4, 0.6}, 0.1, 0.2, 0.9});
  EXPECT_DOUBLE_EQ(lo[0], 0.3);
  EXPECT_DOUBLE_EQ(lo[1], 0.2);
  EXPECT_DOUBLE_EQ(lo[2], 0.5);
  EXPECT_DOUBLE_EQ(hi[0], 0.5);
  EXPECT_DOUBLE_EQ(hi[1], 0.9);
  EXPECT_DOUBLE_EQ(hi[2], 0.7);
  const auto [elo, ehi] = bounding_box(Extrusion{Circle{{0.0, 1.0}, 0.5}, -2.0, 3.0});
  EXPECT_DOUBLE_EQ(elo[1], 0.5);
  EXPECT_DOUBLE_EQ(elo[2], -2.0);
  EXPECT_DOUBLE_EQ(ehi[0], 0.5);
  EXPECT_DOUBLE_EQ(ehi[2], 3.0);
}

// A height map: bilinear between its nodes, so a plane is taken exactly; the ground under it from its
// bottom, over its extent only; and the fractions a mesh lays from it hold the volume under it.
TEST(InitialShapes3d, AHeightMapIsTheGroundUnderItsBilinearSurface) {
  // The plane y = 0.2 + 0.3 x + 0.1 z on nodes 0.25 apart over [0, 1] x [0, 1].
  HeightMap plane{{0.0, 0.0}, {0.25, 0.25}, 5, 5, {}};
  for (int r = 0; r < 5; ++r)
    for (int i = 0; i < 5; ++i) plane.heights.push_back(0.2 + 0.3 * 0.25 * i + 0.1 * 0.25 * r);
  for (const auto& [x, z] : {std::array{0.0, 0.0}, std::array{0.37, 0.81}, std::array{1.0, 1.0}, std::array{0.5, 0.9}})
    EXPECT_NEAR(surface_height(plane, x, z), 0.2 + 0.3 * x + 0.1 * z, 1e-15) << x << " " << z;
  EXPECT_TRUE(contains(plane, 0.5, 0.34, 0.5));    // the surface is at 0.40 there
  EXPECT_FALSE(contains(plane, 0.5, 0.41, 0.5));
  // Half a spacing beyond the outer nodes the surface is level with them; further out, nothing.
  EXPECT_TRUE(contains(plane, 1.1, 0.5 + 0.05 - 1e-9, 0.5));
  EXPECT_FALSE(contains(plane, 1.1, 0.5 + 0.05 + 1e-9, 0.5));
  EXPECT_FALSE(contains(plane, 1.13, 0.0, 0.5));
  EXPECT_TRUE(contains(plane, 0.5, -5.0, 0.5));    // no bottom: all the way down
  HeightMap slab = plane;
  slab.bottom = 0.1;
  EXPECT_FALSE(contains(slab, 0.5, 0.05, 0.5));
  const auto [lo, hi] = bounding_box(slab);
  EXPECT_EQ(lo, (Point3{-0.125, 0.1, -0.125}));
  EXPECT_NEAR(hi[1], 0.6, 1e-15);
  // Under the plane from y = 0.1: 0.2 + 0.15 + 0.05 - 0.1 = 0.3 of the unit square.
  EXPECT_NEAR(laid_volume(ShapeUnion3({slab}), 20), 0.3, 1e-3);
  // A saddle, one cell of its grid: bilinear between its corners' 0.9, 0.1, 0.1, 0.9, mean 0.5.
  const HeightMap saddle{{0.0, 0.0}, {1.0, 1.0}, 2, 2, {0.9, 0.1, 0.1, 0.9}};
  EXPECT_NEAR(surface_height(saddle, 0.25, 0.75), 0.4, 1e-15);
  EXPECT_NEAR(laid_volume(ShapeUnion3({saddle}), 20), 0.5, 1e-3);
}

// An elevation model whose nodes are the centres of a mesh's columns (an ESRI grid of the mesh's cells,
// its corner at the mesh's) covers every column: its nodes' coordinates, origin + i spacing, and the
// mesh's centres, lower + (i + 1/2) width, round apart, and the last centre may fall past the last node
// by that round-off; the half spacing the map reaches beyond its outer nodes holds it.
TEST(InitialShapes3d, AHeightMapOfTheMeshsCellsCoversEveryColumn) {
  for (const int n : {7, 15, 40, 41, 97}) {
    const double lower = 0.1, upper = 0.8, width = (upper - lower) / n;
    const HeightMap flat{{lower + 0.5 * width, lower + 0.5 * width}, {width, width}, n, n,
                         std::vector<double>(size_t(n) * n, 0.5)};
    int covered = 0;
    for (int k = 0; k < n; ++k)
      for (int i = 0; i < n; ++i)
        covered += contains(flat, lower + (i + 0.5) * (upper - lower) / n, 0.25, lower + (k + 0.5) * (upper - lower) / n);
    EXPECT_EQ(covered, n * n) << n;
  }
}

// An elevation model cut down to a domain keeps the surface over it: the same heights there from far
// fewer nodes. One that does not reach the domain is kept whole (for the case to say it lies outside).
TEST(InitialShapes3d, AHeightMapCutToTheDomainKeepsItsSurfaceThere) {
  HeightMap model{{-3.0, -2.0}, {0.5, 0.25}, 41, 33, {}};
  for (int r = 0; r < model.nz; ++r)
    for (int i = 0; i < model.nx; ++i) model.heights.push_back(std::sin(0.7 * i) + std::cos(0.3 * r) + 0.01 * i * r);
  const HeightMap cut = cropped(model, {1.2, 4.1}, {0.3, 0.9});
  EXPECT_EQ(cut.nx, 8);  // nodes at x = 1.0 .. 4.5
  EXPECT_EQ(cut.nz, 4);  // z = 0.25 .. 1.0
  double largest = 0.0;
  for (double x = 1.2; x <= 4.1; x += 0.037)
    for (double z = 0.3; z <= 0.9; z += 0.021)
      largest = std::max(largest, std::abs(surface_height(cut, x, z) - surface_height(model, x, z)));
  EXPECT_LT(largest, 1e-12);
  // A range narrower than a spacing keeps two nodes; one beyond the model keeps it whole.
  EXPECT_EQ(cropped(model, {1.1, 1.2}, {0.3, 0.31}).nx, 2);
  EXPECT_EQ(cropped(model, {1.0, 1.0}, {0.3, 0.31}).nx, 2);
  EXPECT_EQ(cropped(model, {50.0, 60.0}, {0.3, 0.9}).heights.size(), model.heights.size());
}

// A height map's grid finer than the cells: a spike between the nine probes of a cell (its corners
// and centre) is sampled, as a shape smaller than the cell is.
TEST(InitialShapes3d, AHeightMapFinerThanTheCellIsSampled) {
  // Flat at y = -1 under the cell [0, 1]^3 but for one node at (0.3, 0.3) raised to y = 2.
  HeightMap spike{{0.0, 0.0}, {0.1, 0.1}, 11, 11, std::vector<double>(121, -1.0)};
  spike.heights[3 * 11 + 3] = 2.0;
  const ShapeUnion3 u({spike});
  EXPECT_FALSE(u.contains(0.5, 0.5, 0.5));
  // The pyramid over the node's four cells: base 0.2 x 0.2, 3 high, of which the part above y = 0.
  const double inside = u.fraction({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0});
  EXPECT_GT(inside, 0.0);
  EXPECT_LT(inside, 0.04);
}

}  // namespace
}  // namespace granflow::interface
