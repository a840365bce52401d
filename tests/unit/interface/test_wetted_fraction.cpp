#include "models/interface/wetted_fraction.hpp"

#include <gtest/gtest.h>

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
  double side(int axis, int sign) {
    return wetted_side_fraction(rows.data() + 2, widths.data() + 2, widths.data() + 2, 0, 0, axis, sign);
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

}  // namespace
}  // namespace granflow::interface
