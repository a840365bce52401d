// The ParaView series (src/io/vtk_series.hpp): cell data compressed in the appended section, read
// back here as VTK's reader reads them, bit for bit.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "io/vtk_series.hpp"
#include "mesh/field.hpp"
#include "mesh/gather.hpp"

namespace granflow {
namespace {

namespace fs = std::filesystem;

std::uint64_t word(const std::string& blob, std::size_t at) {
  std::uint64_t w;
  std::memcpy(&w, blob.data() + at, sizeof w);
  return w;
}

// Decodes one array of the appended section at `offset`: the UInt64 header of block sizes, then each
// block uncompressed on its own.
std::vector<double> decode(const std::string& blob, std::size_t offset, std::uint64_t* blocks_out = nullptr) {
  const std::uint64_t blocks = word(blob, offset), block = word(blob, offset + 8), last = word(blob, offset + 16);
  if (blocks_out) *blocks_out = blocks;
  std::string bytes;
  std::size_t at = offset + 8 * (3 + blocks);
  for (std::uint64_t k = 0; k < blocks; ++k) {
    const std::uint64_t packed = word(blob, offset + 8 * (3 + k));
    uLongf size = static_cast<uLongf>(k + 1 == blocks && last ? last : block);
    std::string out(size, '\0');
    EXPECT_EQ(uncompress(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(blob.data() + at),
                         static_cast<uLong>(packed)),
              Z_OK);
    EXPECT_EQ(size, k + 1 == blocks && last ? last : block);
    bytes += out;
    at += packed;
  }
  std::vector<double> values(bytes.size() / sizeof(double));
  std::memcpy(values.data(), bytes.data(), bytes.size());
  return values;
}

TEST(VtkSeries, CellDataAreCompressedAndReadBackExactly) {
  GridSpec spec;
  spec.cells = {100, 50, 1};
  spec.upper = {1.0, 0.5};
  const Grid grid(PETSC_COMM_SELF, spec);
  const std::size_t cells = 100 * 50;
  // Values a text format would round: thirds, tiny and huge magnitudes, a signed zero, a subnormal.
  std::vector<double> velocity(3 * cells), pressure(cells, 0.0);
  for (std::size_t k = 0; k < velocity.size(); ++k) velocity[k] = std::sin(0.37 * double(k)) / 3.0 * std::pow(10.0, double(k % 600) - 300.0);
  velocity[1] = -0.0;
  velocity[2] = std::numeric_limits<double>::denorm_min();
  pressure[17] = 101325.0 / 7.0;  // otherwise uniform: compresses well
  const fs::path dir = fs::temp_directory_path() / ("granflow_vtk_series_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  VtkSeries series(dir, "fields");
  series.write(grid, 0.125, {{"velocity", 3, velocity}, {"pressure", 1, pressure}});

  std::ifstream in(dir / "fields_00000.vtr", std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string file = buffer.str();
  const std::size_t underscore = file.find("<AppendedData encoding=\"raw\">\n_");
  ASSERT_NE(underscore, std::string::npos);
  const std::string blob = file.substr(underscore + std::strlen("<AppendedData encoding=\"raw\">\n_"));
  const std::string head = file.substr(0, underscore);
  EXPECT_NE(head.find("header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\""), std::string::npos);

  std::smatch m;
  const std::regex velocity_array(R"re(Name="velocity" NumberOfComponents="3" format="appended" offset="(\d+)")re");
  const std::regex pressure_array(R"re(Name="pressure" NumberOfComponents="1" format="appended" offset="(\d+)")re");
  ASSERT_TRUE(std::regex_search(head, m, velocity_array));
  std::uint64_t blocks = 0;
  const auto v = decode(blob, std::stoul(m[1]), &blocks);
  ASSERT_EQ(v.size(), velocity.size());
  EXPECT_EQ(std::memcmp(v.data(), velocity.data(), v.size() * sizeof(double)), 0);  // bit for bit, -0.0 too
  EXPECT_EQ(blocks, 4u);  // 120 000 bytes: three blocks of 32 KiB and a partial one
  ASSERT_TRUE(std::regex_search(head, m, pressure_array));
  const std::size_t pressure_offset = std::stoul(m[1]);
  const auto p = decode(blob, pressure_offset);
  ASSERT_EQ(p.size(), pressure.size());
  EXPECT_EQ(std::memcmp(p.data(), pressure.data(), p.size() * sizeof(double)), 0);
  // A uniform field takes a small fraction of its 40 000 bytes.
  const std::size_t pressure_bytes = blob.size() - pressure_offset;
  EXPECT_LT(pressure_bytes, 1000u);
  // The time stays text, where VTK's readers look for it, and the index lists the file.
  EXPECT_NE(head.find(R"(Name="TimeValue" NumberOfTuples="1" format="ascii">0.125<)"), std::string::npos);
  std::ifstream pvd(dir / "fields.pvd");
  std::stringstream index;
  index << pvd.rdbuf();
  EXPECT_NE(index.str().find(R"(<DataSet timestep="0.125" file="fields_00000.vtr"/>)"), std::string::npos);
  fs::remove_all(dir);
}

// A mesh of several layers: its z extent and faces, and the cells in natural order (x fastest, then y,
// then z) as the gather gives them and VTK reads them.
TEST(VtkSeries, LayersHaveTheirZFacesAndCellsInVtksOrder) {
  GridSpec spec;
  spec.cells = {4, 3, 5};
  spec.lower = {0.0, 0.0, -1.0};
  spec.upper = {0.4, 0.3, 1.5};
  spec.grading = {1.0, 1.0, 2.0};
  const Grid grid(PETSC_COMM_SELF, spec);
  Field f(grid);
  {
    FieldArray a(grid.field_dm(), f.global());
    for (int k = 0; k < 5; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 4; ++i) a.volume()[k][j][i] = i + 10.0 * j + 100.0 * k;
  }
  const std::vector<double> values = gather_to_root(grid, f);
  const fs::path dir = fs::temp_directory_path() / ("granflow_vtk_layers_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  VtkSeries series(dir, "fields");
  series.write(grid, 0.5, {{"index", 1, values}});
  std::ifstream in(dir / "fields_00000.vtr", std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string file = buffer.str();
  EXPECT_NE(file.find(R"(<RectilinearGrid WholeExtent="0 4 0 3 0 5">)"), std::string::npos);
  EXPECT_NE(file.find(R"(<Piece Extent="0 4 0 3 0 5">)"), std::string::npos);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(file, m, std::regex(R"re(Name="z" format="ascii">\n([^<]*)</DataArray>)re")));
  std::istringstream faces(m[1]);
  std::vector<double> z;
  for (double v; faces >> v;) z.push_back(v);
  ASSERT_EQ(z.size(), 6u);
  EXPECT_NEAR(z.front(), -1.0, 1e-12);
  EXPECT_NEAR(z.back(), 1.5, 1e-12);
  EXPECT_NEAR((z[5] - z[4]) / (z[1] - z[0]), 2.0, 1e-9);
  const std::size_t underscore = file.find("<AppendedData encoding=\"raw\">\n_");
  ASSERT_NE(underscore, std::string::npos);
  const auto v = decode(file.substr(underscore + std::strlen("<AppendedData encoding=\"raw\">\n_")), 0);
  ASSERT_EQ(v.size(), 60u);
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) EXPECT_EQ(v[(k * 3 + j) * 4 + i], i + 10.0 * j + 100.0 * k);
  fs::remove_all(dir);
}

// An array of whole blocks has no partial last block (size 0 in the header, as VTK writes it), and an
// empty one no blocks.
TEST(VtkSeries, WholeBlocksAndEmptyArrays) {
  const std::vector<double> whole(4096, 2.5);  // 32 768 bytes, one block
  const std::string packed = vtk_compressed_array(whole);
  EXPECT_EQ(word(packed, 0), 1u);
  EXPECT_EQ(word(packed, 8), 32768u);
  EXPECT_EQ(word(packed, 16), 0u);
  EXPECT_EQ(decode(packed, 0), whole);
  const std::string empty = vtk_compressed_array({});
  EXPECT_EQ(empty.size(), 3 * sizeof(std::uint64_t));
  EXPECT_EQ(word(empty, 0), 0u);
}

}  // namespace
}  // namespace granflow
