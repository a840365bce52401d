// PLIC geometry on a 3D cell: the soil under a plane against the inclusion-exclusion formula, the
// inversion to round-off down to nearly axis-aligned planes, sub-boxes and faces consistent with the
// whole cell, the 2D geometry recovered by a plane parallel to z, and Youngs' normal exact for planes
// along the grid's axes and diagonals.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "models/interface/plic_geometry.hpp"
#include "models/interface/plic_geometry_3d.hpp"

namespace granflow::interface {
namespace {

// The unit cube's volume where m.X <= a for m > 0 by inclusion-exclusion over the cube's corners
// (each corner beyond the plane adds or takes off a tetrahedron): independent of the branches.
double inclusion_exclusion(double m1, double m2, double m3, double a) {
  const double m[3] = {m1, m2, m3};
  double sum = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    double shift = 0.0;
    int bits = 0;
    for (int d = 0; d < 3; ++d)
      if (corner & (1 << d)) shift += m[d], ++bits;
    const double t = std::max(0.0, a - shift);
    sum += (bits % 2 ? -1.0 : 1.0) * t * t * t;
  }
  return sum / (6.0 * m1 * m2 * m3);
}

Normal3 random_normal(std::mt19937& rng, double smallest = 0.0) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (;;) {
    double m[3] = {u(rng), u(rng), u(rng)};
    const double s = std::abs(m[0]) + std::abs(m[1]) + std::abs(m[2]);
    if (!(s > 0.0)) continue;
    Normal3 n{m[0] / s, m[1] / s, m[2] / s};
    if (std::min({std::abs(n.nx), std::abs(n.ny), std::abs(n.nz)}) >= smallest) return n;
  }
}

TEST(PlicGeometry3d, CubeFractionIsTheInclusionExclusionVolume) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  for (int t = 0; t < 20000; ++t) {
    const Normal3 n = random_normal(rng, 0.05);
    const double a = u(rng);  // in the reflected frame, over the whole range
    const double m1 = std::abs(n.nx), m2 = std::abs(n.ny), m3 = std::abs(n.nz);
    worst = std::max(worst, std::abs(unit_cube_fraction(m1, m2, m3, a) - inclusion_exclusion(m1, m2, m3, a)));
  }
  EXPECT_LT(worst, 1e-12);
  // Planes along an axis, a face diagonal and a body diagonal.
  EXPECT_NEAR(cube_fraction({0.0, 0.0, 1.0}, 0.2), 0.7, 1e-15);
  EXPECT_NEAR(cube_fraction({0.0, -1.0, 0.0}, 0.2), 0.7, 1e-15);
  EXPECT_NEAR(cube_fraction({0.5, 0.5, 0.0}, 0.0), 0.5, 1e-15);
  EXPECT_NEAR(cube_fraction({1.0 / 3, 1.0 / 3, 1.0 / 3}, -0.5 + 0.1), 0.3 * 0.3 * 0.3 / 6.0, 1e-15)
      << "the corner's tetrahedron of legs 0.3";
  EXPECT_EQ(cube_fraction({1.0 / 3, 1.0 / 3, 1.0 / 3}, -0.5), 0.0);
  EXPECT_EQ(cube_fraction({1.0 / 3, 1.0 / 3, 1.0 / 3}, 0.5), 1.0);
}

TEST(PlicGeometry3d, OppositeSidesOfAPlaneFillTheCell) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int t = 0; t < 2000; ++t) {
    const Normal3 n = random_normal(rng);
    const double alpha = u(rng);
    EXPECT_NEAR(cube_fraction(n, alpha) + cube_fraction({-n.nx, -n.ny, -n.nz}, -alpha), 1.0, 1e-15);
  }
}

TEST(PlicGeometry3d, APlaneParallelToZIsThe2dLine) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0), f(0.0, 1.0);
  for (int t = 0; t < 2000; ++t) {
    const double mx = u(rng), my = u(rng), s = std::abs(mx) + std::abs(my);
    const Normal2 n2{mx / s, my / s};
    const Normal3 n3{mx / s, my / s, 0.0};
    const double alpha = 0.5 * u(rng), c = f(rng);
    EXPECT_NEAR(cube_fraction(n3, alpha), cell_fraction(n2, alpha), 1e-15);
    EXPECT_NEAR(plane_alpha(c, n3), line_alpha(c, n2), 1e-14);
  }
}

TEST(PlicGeometry3d, ThePlaneHoldsTheFractionToRoundOffDownToNearlyAlignedPlanes) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> f(0.0, 1.0);
  std::vector<Normal3> normals;
  for (int t = 0; t < 3000; ++t) normals.push_back(random_normal(rng));
  // Nearly and exactly axis-aligned or face-diagonal planes, where the branches' divisions are smallest.
  for (double e : {1e-3, 1e-8, 1e-13, 1e-300, 0.0}) {
    normals.push_back({e, 0.4, 0.6 - e});
    normals.push_back({-e, e, 1.0 - 2 * e});
    normals.push_back({0.5 - e, -0.5, e});
    normals.push_back({1.0 / 3, 1.0 / 3 - e, -1.0 / 3 - e});
  }
  double worst = 0.0;
  for (const Normal3& n : normals)
    for (double c : {0.0, 1e-14, 1e-9, 1e-3, f(rng), 0.5, f(rng), 1.0 - 1e-9, 1.0 - 1e-14, 1.0}) {
      const double alpha = plane_alpha(c, n);
      ASSERT_TRUE(std::isfinite(alpha));
      worst = std::max(worst, std::abs(cube_fraction(n, alpha) - c));
    }
  EXPECT_LT(worst, 1e-14);  // 4e-15 here: the centred plane constant's round-off, times the section
}

TEST(PlicGeometry3d, SubBoxesAndFacesAgreeWithTheWholeCell) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int t = 0; t < 500; ++t) {
    const Normal3 n = random_normal(rng);
    const double alpha = u(rng);
    EXPECT_NEAR(box_fraction(n, alpha, {-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}), cube_fraction(n, alpha), 1e-15);
    // The eight octants hold the cell's soil between them.
    double octants = 0.0;
    for (int o = 0; o < 8; ++o) {
      std::array<double, 3> lo, hi;
      for (int d = 0; d < 3; ++d) {
        lo[d] = (o >> d) & 1 ? 0.0 : -0.5;
        hi[d] = lo[d] + 0.5;
      }
      octants += box_fraction(n, alpha, lo, hi) / 8.0;
    }
    EXPECT_NEAR(octants, cube_fraction(n, alpha), 1e-14);
    // A face's share is the limit of the slab beside it.
    for (int axis = 0; axis < 3; ++axis)
      for (int sign : {-1, 1}) {
        std::array<double, 3> lo{-0.5, -0.5, -0.5}, hi{0.5, 0.5, 0.5};
        (sign > 0 ? lo : hi)[axis] = sign * (0.5 - 1e-7);
        EXPECT_NEAR(face_fraction(n, alpha, axis, sign), box_fraction(n, alpha, lo, hi), 2e-6)
            << "axis " << axis << ", side " << sign;
      }
  }
  // A face the plane only touches is soil where the soil lies along it.
  EXPECT_EQ(face_fraction({1.0, 0.0, 0.0}, 0.5, 0, 1), 1.0);
  EXPECT_EQ(face_fraction({-1.0, 0.0, 0.0}, -0.5, 0, -1), 0.0);
  EXPECT_EQ(face_fraction({0.0, 0.0, 1.0}, 0.5, 2, 1), 1.0);
}

// The block of fractions a plane n.x = d (physical coordinates about the centre cell's centre) gives
// on cells of the widths given, each cell's fraction exactly from its own plane constant.
Block3x3x3 block_under(Normal3 n, double d, const std::array<double, 3>& dx, const std::array<double, 3>& dy,
                       const std::array<double, 3>& dz) {
  Block3x3x3 b;
  auto centre = [](const std::array<double, 3>& w, int i) {
    return i == 1 ? 0.0 : (i == 0 ? -0.5 * (w[0] + w[1]) : 0.5 * (w[1] + w[2]));
  };
  for (int q = 0; q < 3; ++q) b.dx[q] = dx[q], b.dy[q] = dy[q], b.dz[q] = dz[q];
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        // In the cell's scaled coordinates: n.x = d becomes (nx dx) X + ... = d - n.centre.
        const double alpha = d - n.nx * centre(dx, i) - n.ny * centre(dy, j) - n.nz * centre(dz, k);
        b.c[k][j][i] = unit_cube_fraction(n.nx * dx[i], n.ny * dy[j], n.nz * dz[k],
                                          alpha + 0.5 * (n.nx * dx[i] + n.ny * dy[j] + n.nz * dz[k]));
      }
  return b;
}

TEST(PlicGeometry3d, YoungsNormalIsExactForPlanesAlongTheAxesAndDiagonals) {
  const std::array<double, 3> h{1.0, 1.0, 1.0};
  for (const Normal3 n : {Normal3{1.0, 0.0, 0.0}, {0.0, -1.0, 0.0}, {0.0, 0.0, 1.0}, {0.5, 0.5, 0.0},
                          {0.0, -0.5, 0.5}, {1.0 / 3, 1.0 / 3, 1.0 / 3}, {-1.0 / 3, 1.0 / 3, -1.0 / 3}})
    for (double d : {0.0, 0.1}) {
      const Normal3 y = youngs_normal(block_under(n, d, h, h, h));
      EXPECT_NEAR(y.nx, n.nx, 1e-14);
      EXPECT_NEAR(y.ny, n.ny, 1e-14);
      EXPECT_NEAR(y.nz, n.nz, 1e-14);
    }
  // On graded cells a plane across one axis keeps its direction, scaled into the cell's coordinates.
  const Normal3 y = youngs_normal(block_under({0.0, 0.0, 1.0}, 0.1, {1.0, 2.0, 4.0}, {0.5, 0.5, 1.0}, {0.5, 1.0, 2.0}));
  EXPECT_NEAR(y.nz, 1.0, 1e-14);
  // A general plane comes out close (first order), and in physical coordinates again.
  const Normal3 n{0.2, -0.3, 0.5};
  const Normal3 g = to_physical(youngs_normal(block_under(n, 0.05, h, h, h)), 1.0, 1.0, 1.0);
  EXPECT_NEAR(g.nx, n.nx, 0.05);
  EXPECT_NEAR(g.ny, n.ny, 0.05);
  EXPECT_NEAR(g.nz, n.nz, 0.05);
  EXPECT_EQ(youngs_normal(block_under(n, 10.0, h, h, h)).nx, 0.0) << "a block of soil has no normal";
}

// Planes steeper than the body diagonal along one axis, whose heights along it the block brackets:
// the mixed normal has them exactly on uniform cells, where Youngs' is off. On graded cells the
// heights' normal is still exact, but Youngs' (inexact there) may be taken in its place, as in 2D:
// an error of the order of the grading (2.1e-3 at most here, with neighbours' widths 10-40 % apart).
TEST(PlicGeometry3d, MixedNormalIsExactForPlanesTheBlocksHeightsBracket) {
  const std::array<double, 3> h{1.0, 1.0, 1.0}, gx{0.8, 1.0, 1.3}, gy{1.2, 1.0, 0.9}, gz{0.7, 1.0, 1.4};
  double youngs_worst = 0.0;
  for (const Normal3 n : {Normal3{0.15, -0.25, 0.6}, {-0.1, 0.7, 0.2}, {0.55, 0.3, -0.15}, {-0.6, -0.2, -0.2}})
    for (double d : {0.0, 0.12}) {
      for (const bool graded : {false, true}) {
        const Block3x3x3 b = graded ? block_under(n, d, gx, gy, gz) : block_under(n, d, h, h, h);
        const Normal3 m = to_physical(myc_normal(b), b.dx[1], b.dy[1], b.dz[1]);
        const double tolerance = graded ? 3e-3 : 1e-14;
        EXPECT_NEAR(m.nx, n.nx, tolerance) << n.nx << " " << n.ny << " " << n.nz << (graded ? " graded" : "");
        EXPECT_NEAR(m.ny, n.ny, tolerance) << n.nx << " " << n.ny << " " << n.nz << (graded ? " graded" : "");
        EXPECT_NEAR(m.nz, n.nz, tolerance) << n.nx << " " << n.ny << " " << n.nz << (graded ? " graded" : "");
      }
      const Normal3 y = youngs_normal(block_under(n, d, h, h, h));
      youngs_worst = std::max({youngs_worst, std::abs(y.nx - n.nx), std::abs(y.ny - n.ny), std::abs(y.nz - n.nz)});
    }
  EXPECT_GT(youngs_worst, 1e-2) << "Youngs' normal is exact for these planes too: the test shows nothing";
  EXPECT_EQ(myc_normal(block_under({0.2, 0.3, 0.5}, 10.0, h, h, h)).nx, 0.0) << "a block of soil has no normal";
}

}  // namespace
}  // namespace granflow::interface
