// Iso-lines by marching squares over the cell centres (src/io/contour.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "io/contour.hpp"

namespace granflow {
namespace {

// One square of four cell centres, (0.5, 0.5) to (1.5, 1.5) on a 2 x 2 grid of unit cells.
Grid unit_square_grid() {
  GridSpec spec;
  spec.cells = {2, 2, 1};
  spec.upper = {2.0, 2.0};
  return Grid(PETSC_COMM_SELF, spec);
}

// Whether segment s runs between the two edges that meet at corner (cx, cy), cutting it off.
bool cuts_off(const Segment& s, double cx, double cy) {
  const bool first_on_x = std::abs(s.x0 - cx) < 1e-12, second_on_x = std::abs(s.x1 - cx) < 1e-12;
  const bool first_on_y = std::abs(s.y0 - cy) < 1e-12, second_on_y = std::abs(s.y1 - cy) < 1e-12;
  return (first_on_x && second_on_y) || (first_on_y && second_on_x);
}

// A single crossing: one segment, through the interpolated points.
TEST(Contour, StraightLineThroughASquare) {
  const Grid g = unit_square_grid();
  const auto s = iso_line(g, {0.0, 1.0, 0.0, 1.0}, 0.5);  // natural order: (0,0) (1,0) (0,1) (1,1)
  ASSERT_EQ(s.size(), 1u);
  // c = 0.5 halfway between the centres at x = 0.5 and 1.5, on the square's lower and upper edges.
  EXPECT_DOUBLE_EQ(s[0].x0, 1.0);
  EXPECT_DOUBLE_EQ(s[0].x1, 1.0);
  EXPECT_DOUBLE_EQ(std::min(s[0].y0, s[0].y1), 0.5);
  EXPECT_DOUBLE_EQ(std::max(s[0].y0, s[0].y1), 1.5);
}

// A saddle: soil (1) at two opposite corners, air (0.1) at the others. The centre's mean, 0.55, is
// soil, so the soil corners are joined through the middle and the lines cut off the air corners;
// with the centre on the air side (0.45) they cut off the soil corners.
TEST(Contour, SaddleJoinsTheCornersOnTheCentresSide) {
  const Grid g = unit_square_grid();
  // Corners (0.5, 0.5) and (1.5, 1.5) soil; (1.5, 0.5) and (0.5, 1.5) air.
  const auto soil_centre = iso_line(g, {1.0, 0.1, 0.1, 1.0}, 0.5);
  ASSERT_EQ(soil_centre.size(), 2u);
  EXPECT_TRUE(cuts_off(soil_centre[0], 1.5, 0.5) || cuts_off(soil_centre[1], 1.5, 0.5));
  EXPECT_TRUE(cuts_off(soil_centre[0], 0.5, 1.5) || cuts_off(soil_centre[1], 0.5, 1.5));
  const auto air_centre = iso_line(g, {0.9, 0.0, 0.0, 0.9}, 0.5);  // centre 0.45
  ASSERT_EQ(air_centre.size(), 2u);
  EXPECT_TRUE(cuts_off(air_centre[0], 0.5, 0.5) || cuts_off(air_centre[1], 0.5, 0.5));
  EXPECT_TRUE(cuts_off(air_centre[0], 1.5, 1.5) || cuts_off(air_centre[1], 1.5, 1.5));
}

}  // namespace
}  // namespace granflow
