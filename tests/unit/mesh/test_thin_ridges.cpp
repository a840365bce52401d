// Ridges one cell wide lowered to the mesh (mesh/thin_ridges.hpp): columns that stand above both their
// neighbours along x or z come down to the higher of the two, and nothing else is opened.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "mesh/thin_ridges.hpp"

namespace granflow {
namespace {

// A mask of columns: heights[k][i] blocked cells from the bottom of each (x, z) column, ny high.
std::vector<double> columns(const std::vector<std::vector<int>>& heights, int ny) {
  const int nz = int(heights.size()), nx = int(heights[0].size());
  std::vector<double> mask(size_t(nx) * ny * nz, 0.0);
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < heights[k][i]; ++j) mask[(size_t(k) * ny + j) * nx + i] = 1.0;
  return mask;
}

std::vector<std::vector<int>> heights_of(const std::vector<double>& mask, int nx, int ny, int nz) {
  std::vector<std::vector<int>> h(size_t(nz), std::vector<int>(size_t(nx), 0));
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j) h[k][i] += mask[(size_t(k) * ny + j) * nx + i] > 0.5;
  return h;
}

const auto any_cell = [](long) { return true; };

TEST(ThinRidges, ASpikeComesDownToItsHigherNeighbour) {
  // Along x only (one layer: z's neighbours lie beyond the domain, closed): the column of 5 between
  // 2 and 3 loses its two top cells; the last column, against the domain's side, is no ridge.
  std::vector<double> mask = columns({{2, 5, 3, 3, 1, 4}}, 6);
  const auto opened = open_thin_ridges(6, 6, 1, false, mask, any_cell);
  EXPECT_EQ(heights_of(mask, 6, 6, 1), (std::vector<std::vector<int>>{{2, 3, 3, 3, 1, 4}}));
  EXPECT_EQ(opened, (std::vector<long>{3 * 6 + 1, 4 * 6 + 1}));  // (j = 3, i = 1), (j = 4, i = 1), ascending
}

TEST(ThinRidges, APeriodicSideMakesTheLastColumnARidge) {
  std::vector<double> mask = columns({{2, 5, 3, 3, 1, 4}}, 6);
  open_thin_ridges(6, 6, 1, true, mask, any_cell);
  EXPECT_EQ(heights_of(mask, 6, 6, 1), (std::vector<std::vector<int>>{{2, 3, 3, 3, 1, 2}}));
}

TEST(ThinRidges, OpeningOneCellMakesItsNeighbourAWallOfOne) {
  // (i = 2, k = 1) is a ridge along z; once it is open, (1, 1) stands between open cells along x.
  std::vector<std::vector<int>> h = {{1, 3, 1}, {1, 3, 3}, {1, 1, 1}};
  std::vector<double> mask = columns(h, 4);
  const auto opened = open_thin_ridges(3, 4, 3, false, mask, any_cell);
  EXPECT_EQ(heights_of(mask, 3, 4, 3), (std::vector<std::vector<int>>{{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}));
  EXPECT_EQ(opened.size(), 6u);
}

TEST(ThinRidges, ACellItMayNotOpenStaysAndHoldsItsColumn) {
  std::vector<double> mask = columns({{1, 4, 1}}, 5);
  const long kept = 2 * 3 + 1;  // (j = 2, i = 1): another obstacle's
  const auto opened = open_thin_ridges(3, 5, 1, false, mask, [&](long n) { return n != kept; });
  EXPECT_EQ(opened, (std::vector<long>{1 * 3 + 1, 3 * 3 + 1}));
  EXPECT_GT(mask[size_t(kept)], 0.5);
}

TEST(ThinRidges, TwoCellsWideIsLeftAsItIs) {
  std::vector<double> mask = columns({{1, 4, 4, 1}, {1, 4, 4, 1}}, 5);
  const std::vector<double> before = mask;
  EXPECT_TRUE(open_thin_ridges(4, 5, 2, false, mask, any_cell).empty());
  EXPECT_EQ(mask, before);
}

// On rough terrain, the cells opened are those a plain sweep opens, one cell at a time and from the
// first cell again after each, until a whole sweep opens none; and no ridge one cell wide is left.
TEST(ThinRidges, RoughTerrainAsOneCellAtATime) {
  std::mt19937 random(12345);
  std::uniform_int_distribution<int> height(0, 7);
  const int nx = 17, ny = 8, nz = 13;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::vector<int>> h(nz, std::vector<int>(nx));
    for (auto& row : h)
      for (int& v : row) v = height(random);
    std::vector<double> mask = columns(h, ny), plain = mask;
    auto index = [&](int i, int j, int k) { return (size_t(k) * ny + j) * nx + i; };
    auto open_in = [&](const std::vector<double>& m, int i, int j, int k) {
      return i >= 0 && i < nx && k >= 0 && k < nz && m[index(i, j, k)] < 0.5;
    };
    auto thin_in = [&](const std::vector<double>& m, int i, int j, int k) {
      return m[index(i, j, k)] > 0.5 && ((open_in(m, i - 1, j, k) && open_in(m, i + 1, j, k)) ||
                                         (open_in(m, i, j, k - 1) && open_in(m, i, j, k + 1)));
    };
    const auto may_open = [&](long n) { return n % 7 != 3; };  // some cells are another obstacle's
    for (bool again = true; again;) {
      again = false;
      for (int k = 0; k < nz && !again; ++k)
        for (int j = 0; j < ny && !again; ++j)
          for (int i = 0; i < nx && !again; ++i)
            if (thin_in(plain, i, j, k) && may_open(long(index(i, j, k)))) {
              plain[index(i, j, k)] = 0.0;
              again = true;
            }
    }
    const auto opened = open_thin_ridges(nx, ny, nz, false, mask, may_open);
    ASSERT_EQ(mask, plain) << "trial " << trial;
    EXPECT_FALSE(opened.empty());
    long left = 0;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) left += thin_in(mask, i, j, k) && may_open(long(index(i, j, k)));
    EXPECT_EQ(left, 0);
  }
}

}  // namespace
}  // namespace granflow
