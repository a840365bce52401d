// Initial soil shapes: whether a shape reaches into the domain at all, and whether a polygon crosses
// itself, the two checks a case file's shapes get.
#include "models/interface/initial_shapes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace granflow::interface {
namespace {

const Point lower{0.0, 0.0}, upper{0.6, 0.2};

TEST(InitialShapes, BoxesOverlapTheDomainOnlyWithSomeArea) {
  EXPECT_TRUE(overlaps(Box{{0.0, 0.0}, {0.2, 0.1}}, lower, upper));
  EXPECT_TRUE(overlaps(Box{{-1.0, -1.0}, {2.0, 2.0}}, lower, upper));  // around the domain
  EXPECT_FALSE(overlaps(Box{{0.6, 0.0}, {0.8, 0.1}}, lower, upper));   // touching its side
  EXPECT_FALSE(overlaps(Box{{0.7, 0.0}, {0.8, 0.1}}, lower, upper));
}

TEST(InitialShapes, CirclesOverlapByTheirDistanceFromTheDomain) {
  // Its bounding box reaches into the domain, the circle does not (a corner of the domain lies
  // 0.141 from its centre).
  EXPECT_FALSE(overlaps(Circle{{0.7, 0.3}, 0.12}, lower, upper));
  EXPECT_TRUE(overlaps(Circle{{0.7, 0.3}, 0.15}, lower, upper));
  EXPECT_TRUE(overlaps(Circle{{0.3, 0.1}, 0.01}, lower, upper));   // inside
  EXPECT_TRUE(overlaps(Circle{{0.3, 0.1}, 10.0}, lower, upper));   // around
  EXPECT_FALSE(overlaps(Circle{{0.3, -0.1}, 0.1}, lower, upper));  // touching the floor
}

// A ring covers some of the domain where its outer disc does and its hole does not hold all of it.
TEST(InitialShapes, RingsOverlapUnlessTheDomainLiesInTheirHole) {
  EXPECT_TRUE(overlaps(Ring{{0.3, 0.1}, 0.01, 0.05}, lower, upper));   // inside
  EXPECT_FALSE(overlaps(Ring{{0.3, 0.1}, 1.0, 2.0}, lower, upper));    // the domain in its hole
  EXPECT_TRUE(overlaps(Ring{{0.3, 0.1}, 0.3, 2.0}, lower, upper));     // the hole holds all but the corners
  EXPECT_FALSE(overlaps(Ring{{0.7, 0.3}, 0.05, 0.12}, lower, upper));  // its box reaches in, the ring does not
  EXPECT_FALSE(overlaps(Ring{{0.3, -0.2}, 0.1, 0.2}, lower, upper));   // touching the floor
  EXPECT_TRUE(contains(Ring{{0.0, 0.0}, 1.0, 2.0}, 1.5, 0.0));
  EXPECT_FALSE(contains(Ring{{0.0, 0.0}, 1.0, 2.0}, 0.5, 0.5));
  EXPECT_FALSE(contains(Ring{{0.0, 0.0}, 1.0, 2.0}, 2.0, 0.1));
}

TEST(InitialShapes, PolygonsOverlapByTheAreaOfTheirPartInside) {
  EXPECT_TRUE(overlaps(Polygon{{{0.1, 0.05}, {0.2, 0.05}, {0.15, 0.1}}}, lower, upper));            // a vertex inside
  EXPECT_TRUE(overlaps(Polygon{{{-1.0, -1.0}, {2.0, -1.0}, {0.3, 3.0}}}, lower, upper));            // around
  EXPECT_TRUE(overlaps(Polygon{{{0.3, -0.1}, {0.4, 0.3}, {0.2, 0.3}}}, lower, upper));              // edges cross
  // On the domain's sides, as a wedge against the wall and the floor.
  EXPECT_TRUE(overlaps(Polygon{{{0.0, 0.0}, {0.3, 0.0}, {0.0, 0.1}}}, lower, upper));
  EXPECT_FALSE(overlaps(Polygon{{{0.0, 0.0}, {0.3, 0.0}, {0.3, -0.1}}}, lower, upper));  // below the floor
  // Its bounding box covers the domain's corner, the triangle does not.
  EXPECT_FALSE(overlaps(Polygon{{{0.5, 0.3}, {0.8, 0.3}, {0.8, 0.1}}}, lower, upper));
}

TEST(InitialShapes, SelfIntersectingPolygonsAreFound) {
  EXPECT_FALSE(self_intersecting(Polygon{{{0.0, 0.0}, {0.2, 0.0}, {0.2, 0.1}, {0.0, 0.1}}}));
  EXPECT_FALSE(self_intersecting(Polygon{{{0.0, 0.0}, {0.2, 0.0}, {0.1, 0.05}, {0.2, 0.1}, {0.0, 0.1}}}));  // concave
  EXPECT_TRUE(self_intersecting(Polygon{{{0.0, 0.0}, {0.2, 0.1}, {0.2, 0.0}, {0.0, 0.1}}}));  // a bow tie
  EXPECT_TRUE(self_intersecting(Polygon{{{0.0, 0.0}, {0.2, 0.0}, {0.1, 0.0}, {0.1, 0.1}}}));  // an edge doubling back
}

// The sweep in x compares only edges whose x ranges overlap; on random polygons (small integer
// coordinates, so that vertices, collinear and touching edges are common) it finds what comparing
// every pair finds.
TEST(InitialShapes, SelfIntersectionSweepAgreesWithComparingEveryPair) {
  auto every_pair = [](const Polygon& p) {
    const auto& v = p.vertices;
    const std::size_t n = v.size();
    auto orient = [](const Point& a, const Point& b, const Point& c) {
      return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    };
    auto on = [](const Point& a, const Point& b, const Point& c) {
      return std::min(a[0], b[0]) <= c[0] && c[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= c[1] &&
             c[1] <= std::max(a[1], b[1]);
    };
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = a + 1; b < n; ++b) {
        if (b == a + 1 || (a == 0 && b == n - 1)) continue;
        const Point &p1 = v[a], &p2 = v[(a + 1) % n], &q1 = v[b], &q2 = v[(b + 1) % n];
        const double o1 = orient(p1, p2, q1), o2 = orient(p1, p2, q2), o3 = orient(q1, q2, p1), o4 = orient(q1, q2, p2);
        if (o1 * o2 < 0 && o3 * o4 < 0) return true;
        if ((o1 == 0 && on(p1, p2, q1)) || (o2 == 0 && on(p1, p2, q2)) || (o3 == 0 && on(q1, q2, p1)) ||
            (o4 == 0 && on(q1, q2, p2)))
          return true;
      }
    return false;
  };
  std::mt19937 random(7);
  std::uniform_int_distribution<int> coordinate(0, 6), size(3, 9);
  int crossing = 0, simple = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Polygon p;
    for (int k = size(random); k > 0; --k) p.vertices.push_back({double(coordinate(random)), double(coordinate(random))});
    const bool expected = every_pair(p);
    ASSERT_EQ(self_intersecting(p), expected) << "trial " << trial;
    (expected ? crossing : simple) += 1;
  }
  EXPECT_GT(simple, 500);  // both outcomes are exercised
  EXPECT_GT(crossing, 500);
}

// The prepared union tests only the edges at a query's height; its answers are those of testing
// every edge: on random polygons with vertices on a coarse lattice (so queries fall exactly on vertex
// heights and edges), a terrain profile of many vertices and a comb of tall spikes, at points inside,
// outside, on the lattice and beyond the shapes' bounding boxes.
TEST(InitialShapes, PreparedUnionAnswersAsTestingEveryEdge) {
  std::mt19937 random(11);
  std::uniform_int_distribution<int> coordinate(0, 8), size(3, 12);
  std::uniform_real_distribution<double> anywhere(-1.0, 9.0);
  std::vector<std::vector<Shape>> unions;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<Shape> shapes;
    for (int s = 1 + trial % 3; s > 0; --s) {
      Polygon p;
      for (int k = size(random); k > 0; --k) p.vertices.push_back({double(coordinate(random)), double(coordinate(random))});
      shapes.push_back(p);
    }
    if (trial % 5 == 0) shapes.push_back(Box{{1.0, 1.0}, {3.0, 2.0}});
    unions.push_back(shapes);
  }
  Polygon terrain{{{8.0, 0.0}, {0.0, 0.0}}};  // the floor, then a rough surface from x = 0 to 8
  std::uniform_real_distribution<double> height(1.0, 3.0);
  for (int k = 0; k <= 4000; ++k) terrain.vertices.push_back({8.0 * k / 4000, k % 400 == 0 ? 2.0 : height(random)});
  Polygon comb{{{8.0, 0.0}, {0.0, 0.0}}};  // spikes the whole height: every edge spans every height
  for (int k = 0; k < 400; ++k) {
    comb.vertices.push_back({8.0 * k / 400, 8.0});
    comb.vertices.push_back({8.0 * (k + 0.5) / 400, 0.5});
  }
  unions.push_back({terrain});
  unions.push_back({comb});
  // Heights no bin width can divide: beyond what a double's difference holds, and subnormal.
  unions.push_back({Polygon{{{1.0, -1e308}, {5.0, -1e308}, {5.0, 1e308}, {1.0, 1e308}}}});
  unions.push_back({Polygon{{{1.0, 0.0}, {5.0, 0.0}, {5.0, 1e-310}, {1.0, 1e-310}}}});
  long inside = 0, queries = 0, cut_cells = 0;
  for (const auto& shapes : unions) {
    const ShapeUnion prepared(shapes);
    for (int q = 0; q < 400; ++q) {
      const double x = q % 2 ? anywhere(random) : double(coordinate(random)) - 0.5 + 0.5 * (q % 4 / 2);
      const double y = q % 3 ? anywhere(random) : double(coordinate(random));
      const bool expected = union_contains(shapes, x, y);
      ASSERT_EQ(prepared.contains(x, y), expected) << "query (" << x << ", " << y << ")";
      inside += expected;
      ++queries;
    }
    // Cells: where the five probes (corners and centre) disagree, the same samples give the same
    // fraction to the last bit.
    for (int c = 0; c < 20; ++c) {
      const double x0 = coordinate(random) + 0.25 * (c % 4), y0 = coordinate(random) + 0.25 * (c / 4 % 4);
      const double x1 = x0 + 0.5, y1 = y0 + 0.5;
      const int probes = union_contains(shapes, x0, y0) + union_contains(shapes, x1, y0) +
                         union_contains(shapes, x0, y1) + union_contains(shapes, x1, y1) +
                         union_contains(shapes, 0.5 * (x0 + x1), 0.5 * (y0 + y1));
      if (probes == 0 || probes == 5) continue;
      double expected = 0.0;
      for (int a = 0; a < 32; ++a)
        for (int b = 0; b < 32; ++b) expected += union_contains(shapes, x0 + (a + 0.5) * 0.5 / 32, y0 + (b + 0.5) * 0.5 / 32);
      ASSERT_EQ(prepared.fraction(x0, x1, y0, y1), expected / 1024.0);
      ++cut_cells;
    }
  }
  EXPECT_GT(cut_cells, 500);
  EXPECT_GT(inside, queries / 10);  // both answers are exercised
  EXPECT_LT(inside, queries * 9 / 10);
}

// A shape smaller than the cell, between the cell's corners and centre, is not lost by the fast path
// that reads those five points.
TEST(InitialShapes, AShapeSmallerThanTheCellIsSampled) {
  const std::vector<Shape> small{Circle{{0.305, 0.105}, 0.002}};
  const double f = ShapeUnion(small).fraction(0.3, 0.32, 0.1, 0.12);
  const double exact = 3.14159265 * 0.002 * 0.002 / (0.02 * 0.02);  // 0.0314
  EXPECT_NEAR(f, exact, 0.2 * exact);
  EXPECT_EQ(ShapeUnion(small).fraction(0.32, 0.34, 0.1, 0.12), 0.0);  // the next cell: none
}

// A notch narrower than a cell in a large polygon passes between the five probes of every cell along
// it: those cells are sampled as any other cut cell, to the same bit as the plain sampling (the fast
// path took them as full: 1 where the samples give 0.85).
TEST(InitialShapes, ANotchNarrowerThanTheCellIsSampled) {
  // A 10 x 10 square with a slot 0.15 wide from its top down to y = 2, at x = 0.2 ... 0.35: between
  // the probes of the cells at x = 0 ... 1 (their corners and centre).
  const std::vector<Shape> notched{Polygon{{{0, 0}, {10, 0}, {10, 10}, {0.35, 10}, {0.35, 2}, {0.2, 2}, {0.2, 10}, {0, 10}}}};
  const ShapeUnion prepared(notched);
  int sampled_cells = 0;
  for (int j = 0; j < 10; ++j) {
    const double y0 = j, y1 = j + 1.0;
    double expected = 0.0;
    for (int a = 0; a < 32; ++a)
      for (int b = 0; b < 32; ++b) expected += union_contains(notched, (a + 0.5) / 32, y0 + (b + 0.5) / 32);
    ASSERT_EQ(prepared.fraction(0.0, 1.0, y0, y1), expected / 1024.0) << "row " << j;
    sampled_cells += expected < 1024.0;
  }
  EXPECT_EQ(sampled_cells, 8);  // the slot's rows, y = 2 to 10
  EXPECT_EQ(prepared.fraction(1.0, 2.0, 5.0, 6.0), 1.0);  // beside it: full
}

// Axisymmetric fractions are fractions of the cell's volume: a sphere of radius R on the axis (a
// circle in the r-z plane) holds (2/3) R^3 per radian, which the cells' fractions times their volumes
// r_c dr dz must give. Counted by area, the cut cells near the axis weigh too much (2.2e-3 over at
// 10 cells per radius); a cell cut by a line r = const keeps its volume fraction exactly.
TEST(InitialShapes, AxisymmetricFractionsAreVolumeFractions) {
  const double R = 1.0, h = 0.1;  // 10 cells per radius
  const std::vector<Shape> sphere{Circle{{0.0, 0.0}, R}};
  double volume = 0.0, by_area = 0.0;
  for (int i = 0; i < 12; ++i)
    for (int j = -12; j < 12; ++j) {
      const double r0 = i * h, z0 = j * h, rc = r0 + 0.5 * h;
      volume += ShapeUnion(sphere).fraction(r0, r0 + h, z0, z0 + h, true) * rc * h * h;
      by_area += ShapeUnion(sphere).fraction(r0, r0 + h, z0, z0 + h, false) * rc * h * h;
    }
  const double exact = 2.0 / 3.0 * R * R * R;
  EXPECT_NEAR(volume / exact, 1.0, 1e-4);
  EXPECT_GT(std::abs(by_area / exact - 1.0), 1e-3);
  // A cylinder r < 0.25 in the cell [0, 0.5] x [0, 1]: a quarter of its area but (0.25/0.5)^2 of its volume.
  const std::vector<Shape> cylinder{Box{{0.0, 0.0}, {0.25, 1.0}}};
  EXPECT_NEAR(ShapeUnion(cylinder).fraction(0.0, 0.5, 0.0, 1.0, true), 0.25, 1e-12);
  EXPECT_NEAR(ShapeUnion(cylinder).fraction(0.0, 0.5, 0.0, 1.0, false), 0.5, 1e-12);
}

// A ring's cells hold its area, pi (R^2 - r^2), planar; and drawn in the r-z plane of an axisymmetric
// mesh, the torus's volume per radian, the section's area times its centre's radius (Pappus). A hole
// smaller than a cell, off the cell's centre, where the cell's corners and centre all lie in the
// ring, is found: the cell is not taken as full.
TEST(InitialShapes, RingsHoldTheirAreaAndTheirTorusVolume) {
  const double inner = 0.1, outer = 0.2, h = 0.01;
  const std::vector<Shape> planar{Ring{{0.0, 0.0}, inner, outer}};
  double area = 0.0;
  for (int i = -25; i < 25; ++i)
    for (int j = -25; j < 25; ++j) area += ShapeUnion(planar).fraction(i * h, (i + 1) * h, j * h, (j + 1) * h) * h * h;
  EXPECT_NEAR(area / (M_PI * (outer * outer - inner * inner)), 1.0, 2e-4);

  const double r0 = 0.5;  // the section's centre, off the axis
  const std::vector<Shape> torus{Ring{{r0, 0.0}, inner, outer}};
  double volume = 0.0;
  for (int i = 25; i < 75; ++i)
    for (int j = -25; j < 25; ++j)
      volume += ShapeUnion(torus).fraction(i * h, (i + 1) * h, j * h, (j + 1) * h, true) * (i + 0.5) * h * h * h;
  EXPECT_NEAR(volume / (M_PI * (outer * outer - inner * inner) * r0), 1.0, 2e-4);

  // A band thinner than the cells (a fifth of one), which can pass between a cell's corners and centre.
  const std::vector<Shape> thin{Ring{{0.0, 0.0}, 0.2, 0.202}};
  double thin_area = 0.0;
  for (int i = -25; i < 25; ++i)
    for (int j = -25; j < 25; ++j) thin_area += ShapeUnion(thin).fraction(i * h, (i + 1) * h, j * h, (j + 1) * h) * h * h;
  EXPECT_NEAR(thin_area / (M_PI * (0.202 * 0.202 - 0.2 * 0.2)), 1.0, 0.02);

  const std::vector<Shape> small_hole{Ring{{0.3, 0.3}, 0.1, 2.0}};
  EXPECT_NEAR(ShapeUnion(small_hole).fraction(0.0, 1.0, 0.0, 1.0), 1.0 - M_PI * 0.01, 2e-3);
  EXPECT_EQ(ShapeUnion(small_hole).fraction(1.0, 2.0, 0.0, 1.0), 1.0);  // beside the hole: full
}

}  // namespace
}  // namespace granflow::interface
