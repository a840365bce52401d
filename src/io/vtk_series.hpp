#pragma once
// ParaView time series: one VTK XML rectilinear-grid file (.vtr) per output time with cell data,
// indexed by a .pvd collection that is rewritten whole after each file. The cell data are binary,
// zlib-compressed, in the file's appended section (exact doubles); coordinates and time are text.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "mesh/grid.hpp"

namespace granflow {

struct CellData {
  std::string name;
  int components = 1;          // 1 (scalar) or 3 (vector, xyz interleaved)
  std::vector<double> values;  // natural order, size cells * components
};

// One array in VTK's compressed binary layout (header_type UInt64, vtkZLibDataCompressor): the header
// of block sizes, then the zlib blocks. What follows "_" in the appended section, per array.
std::string vtk_compressed_array(const std::vector<double>& values);

class VtkSeries {
 public:
  VtkSeries(std::filesystem::path directory, std::string basename);
  // Rank 0 writes; other ranks may pass empty data and return immediately.
  void write(const Grid& grid, double time, const std::vector<CellData>& data);
  const std::filesystem::path& index_file() const { return pvd_; }
  // The files written so far (rank 0), and the same list taken back when a run restarts.
  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }
  void restore_entries(std::vector<std::pair<double, std::string>> entries) { entries_ = std::move(entries); }

 private:
  std::filesystem::path dir_, pvd_;
  std::string base_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace granflow
