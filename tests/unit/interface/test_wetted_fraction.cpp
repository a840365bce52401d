#include "models/interface/wetted_fraction.hpp"

#include <gtest/gtest.h>

#include "models/interface/plic_geometry.hpp"

#include <array>
#include <vector>

namespace granflow::interface {
namespace {

// A 5 x 5 ghosted patch (global indices -2..2 around cell (0, 0)) of unit cells.
struct Patch {
  std::array<std::array<double, 5>, 5> c{};
  std::array<double*, 5> rows{};
  std::array<double, 5> widths{1, 1, 1, 1, 1};
  Patch() {
    for (int j = 0; j < 5; ++j) rows[j] = c[j].data() + 2;
  }
  double& at(int i, int j) { return c[j + 2][i + 2]; }
  const double* radii = nullptr;  // centre radii, indexed like widths: axisymmetric
  double side(int axis, int sign) {
    return wetted_side_fraction(rows.data() + 2, widths.data() + 2, widths.data() + 2, 0, 0, axis, sign, radii);
  }
};

TEST(WettedFraction, AFilmOnTheFloorCoversAllOfIt) {
  Patch p;
  for (int i = -2; i <= 2; ++i) {
    p.at(i, -1) = 0.1;  // the wall's mirror ghost
    p.at(i, 0) = 0.1;
  }
  EXPECT_EQ(p.side(1, -1), 1.0);
  EXPECT_EQ(p.side(1, +1), 0.0);
  EXPECT_NEAR(p.side(0, -1), 0.1, 1e-15);
}

TEST(WettedFraction, AnInterfaceAcrossTheSideCoversItsFraction) {
  Patch p;
  for (int j = -2; j <= 2; ++j) {
    p.at(-1, j) = 1.0;
    p.at(0, j) = 0.3;  // a vertical front, soil on the west
  }
  EXPECT_NEAR(p.side(1, -1), 0.3, 1e-15);
  EXPECT_EQ(p.side(0, -1), 1.0);
  EXPECT_EQ(p.side(0, +1), 0.0);
}

TEST(WettedFraction, PureAndFlatCellsKeepTheirFraction) {
  Patch p;
  EXPECT_EQ(p.side(1, -1), 0.0);
  for (auto& row : p.c) row.fill(1.0);
  EXPECT_EQ(p.side(1, -1), 1.0);
  for (auto& row : p.c) row.fill(0.4);
  EXPECT_EQ(p.side(1, -1), 0.4);
}

// Axisymmetric: c is the soil's share of r dr dz, and the floor's area is the integral of r over it.
// A vertical front still covers the floor's share c (the soil beside the axis weighs less in both),
// and a film on the floor all of it. In the cell on the axis (r from 0 to 1) c = 0.25 is the soil out
// to r = 1/2, half the floor's width and a quarter of its area.
TEST(WettedFraction, AxisymmetricFloorCoversTheShareOfItsArea) {
  for (const double r_west : {0.0, 1.0}) {
    Patch p;
    const std::array<double, 5> centres{r_west - 1.5, r_west - 0.5, r_west + 0.5, r_west + 1.5, r_west + 2.5};
    p.radii = centres.data() + 2;
    for (int j = -2; j <= 2; ++j) {
      p.at(-1, j) = 1.0;
      p.at(0, j) = 0.25;  // a vertical front, soil towards the axis
    }
    EXPECT_NEAR(p.side(1, -1), 0.25, 1e-15) << "cell from r = " << r_west;
    EXPECT_EQ(p.side(0, -1), 1.0);
    EXPECT_EQ(p.side(0, +1), 0.0);
    for (auto& row : p.c) row.fill(0.0);
    for (int i = -2; i <= 2; ++i) p.at(i, -1) = p.at(i, 0) = 0.1;  // a film on the floor
    EXPECT_EQ(p.side(1, -1), 1.0);
    EXPECT_EQ(p.side(1, +1), 0.0);
  }
}

// A sloped front in the cell from r = 2 to 3 (unit cells), the block's fractions the exact weighted
// ones of the line 0.7 X + 0.3 Y <= -0.1 (in the middle cell's coordinates): the floor's covered share
// is the line's to 1e-4 (MYC's normal from weighted fractions is nearly exact this far out). The planar
// line and length fraction give 0.528 against 0.522.
TEST(WettedFraction, AxisymmetricSlopedFrontCoversTheLinesShare) {
  Patch p;
  const double r = 2.5;
  const std::array<double, 5> centres{r - 2, r - 1, r, r + 1, r + 2};
  p.radii = centres.data() + 2;
  const Normal2 n{0.7, 0.3};
  const double alpha = -0.1;
  for (int j = -2; j <= 2; ++j)
    for (int i = -2; i <= 2; ++i)
      p.at(i, j) = weighted_rectangle_fraction(n, alpha - n.nx * i - n.ny * j, centres[i + 2], -0.5, 0.5, -0.5, 0.5);
  EXPECT_NEAR(p.side(1, -1), weighted_side_fraction(n, alpha, 1, -1, r), 1e-3);
}

}  // namespace
}  // namespace granflow::interface
