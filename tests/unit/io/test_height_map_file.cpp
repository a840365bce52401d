// Height maps from ESRI ASCII grids (io/height_map_file.hpp): the header's registrations, the rows
// from the north, and what is refused, each error naming the file and its line.
#include "io/height_map_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/case_error.hpp"

namespace granflow {
namespace {

namespace fs = std::filesystem;

class HeightMapFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("granflow_height_map_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  std::string error(const std::string& text) {
    try {
      read_height_map_file(write("bad.asc", text), "obstacle[0].heights_file");
    } catch (const CaseError& e) {
      return e.what();
    }
    return "no error";
  }
  fs::path dir_;
};

// Three columns and two rows of 10 m cells whose lower-left corner is at (100, 200): the nodes are the
// cells' centres, from (105, 205); the first row read is the northern one, at z = 215.
TEST_F(HeightMapFile, ReadsTheGridFromTheSouthAtTheCellsCentres) {
  const auto map = read_height_map_file(
      write("dem.asc", "ncols 3\nNROWS 2\nxllcorner 100\nyllcorner 200\ncellsize 10\nNODATA_value -9999\n"
                       "7 8 9\n1 2 3\n"),
      "obstacle[0].heights_file");
  EXPECT_EQ(map.nx, 3);
  EXPECT_EQ(map.nz, 2);
  EXPECT_EQ(map.origin, (std::array<double, 2>{105.0, 205.0}));
  EXPECT_EQ(map.spacing, (std::array<double, 2>{10.0, 10.0}));
  EXPECT_EQ(map.heights, (std::vector<double>{1, 2, 3, 7, 8, 9}));
  EXPECT_EQ(interface::surface_height(map, 105.0, 215.0), 7.0);
  // Centre registration, cells of their own width and depth, CRLF line ends and heights over any lines.
  const auto other = read_height_map_file(
      write("other.asc", "ncols 2\r\nnrows 2\r\nxllcenter 0.5\r\nyllcenter -1\r\ndx 2\r\ndy 0.5\r\n1 2\r\n3\r\n4\r\n"),
      "initial.soil[0].heights_file");
  EXPECT_EQ(other.origin, (std::array<double, 2>{0.5, -1.0}));
  EXPECT_EQ(other.spacing, (std::array<double, 2>{2.0, 0.5}));
  EXPECT_EQ(other.heights, (std::vector<double>{3, 4, 1, 2}));
}

TEST_F(HeightMapFile, RefusesWhatIsNotACompleteGrid) {
  const std::string head = "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
  const std::string hole = error(head + "NODATA_value -9999\n1 2\n3 -9999\n");
  EXPECT_NE(hole.find("obstacle[0].heights_file: "), std::string::npos) << hole;
  EXPECT_NE(hole.find("bad.asc:8: no height (NODATA) at row 2, column 2"), std::string::npos) << hole;
  const std::string short_of = error(head + "1 2\n3\n");
  EXPECT_NE(short_of.find("holds 3 heights, not ncols x nrows = 2 x 2 = 4"), std::string::npos) << short_of;
  EXPECT_NE(error(head + "1 2\n3 4\n5\n").find("bad.asc:8: more heights than ncols x nrows"), std::string::npos);
  EXPECT_NE(error(head + "1 2\n3 four\n").find("bad.asc:7: expected a height, found 'four'"), std::string::npos);
  EXPECT_NE(error("ncols 2\nnrows 2\nxllcorner 0\ncellsize 1\n1 2\n3 4\n").find("needs one of yllcorner and yllcenter"),
            std::string::npos);
  EXPECT_NE(error("ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n").find("nrows is 1, not a whole "
                                                                                        "number of at least 2"),
            std::string::npos);
  EXPECT_NE(error("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 0\n1 2\n3 4\n").find("the cell size 0 is not "
                                                                                           "positive"),
            std::string::npos);
  const std::string unknown = error("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncelsize 1\n1 2\n3 4\n");
  EXPECT_NE(unknown.find("bad.asc:5: unknown header key 'celsize'"), std::string::npos) << unknown;
  EXPECT_NE(error("ncols 2\nnrows two\n").find("bad.asc:2: expected a header key and its number"), std::string::npos);
  EXPECT_NE(error(head + "1 2\n3 1e200\n").find("beyond the magnitudes"), std::string::npos);
  // GDAL writes NODATA_value nan: a nan height is then a hole, named as one.
  const std::string nan_hole = error(head + "NODATA_value nan\n1 2\nnan 4\n");
  EXPECT_NE(nan_hole.find("bad.asc:8: no height (NODATA) at row 2, column 1"), std::string::npos) << nan_hole;
  EXPECT_NE(error(head + "1 2\n3 +-4\n").find("expected a height, found '+-4'"), std::string::npos);
  // A header asking for more heights than the file can hold is refused before room is made for them.
  const std::string huge = error("ncols 100000000\nnrows 100000000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n");
  EXPECT_NE(huge.find("asks for ncols x nrows = 100000000 x 100000000 heights, more than the rest of the file (4 "
                      "bytes) can hold"),
            std::string::npos)
      << huge;
  const std::string none = error("");
  EXPECT_NE(none.find("has no ncols in its header"), std::string::npos) << none;
  try {
    read_height_map_file(dir_ / "missing.asc", "obstacle[0].heights_file");
    ADD_FAILURE();
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("obstacle[0].heights_file: cannot open"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace granflow
