#include "io/vtk_series.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "io/atomic_file.hpp"

namespace granflow {

static_assert(std::endian::native == std::endian::little, "the files declare byte_order=\"LittleEndian\"");

std::string vtk_compressed_array(const std::vector<double>& values) {
  // VTK's layout for a compressed binary array with header_type UInt64 (what vtkXMLWriter writes):
  // [number of blocks, block size, size of the last block if partial (else 0), compressed size of each
  // block], then the blocks, each compressed on its own. 32 KiB blocks, as VTK's own writer.
  constexpr std::uint64_t block = 32768;
  const std::uint64_t total = values.size() * sizeof(double);
  const std::uint64_t last = total % block, blocks = total / block + (last ? 1 : 0);
  std::vector<std::uint64_t> header{blocks, block, last};
  std::string body;
  const auto* bytes = reinterpret_cast<const Bytef*>(values.data());
  std::vector<Bytef> packed(compressBound(block));
  for (std::uint64_t k = 0; k < blocks; ++k) {
    const std::uint64_t size = std::min(block, total - k * block);
    uLongf packed_size = static_cast<uLongf>(packed.size());
    // Level 1: fields of granular flows are mostly uniform (soil at rest, still air), and the fastest
    // level takes most of what the slower ones would.
    if (compress2(packed.data(), &packed_size, bytes + k * block, static_cast<uLong>(size), 1) != Z_OK)
      throw std::runtime_error("zlib could not compress a field for the VTK output");
    header.push_back(packed_size);
    body.append(reinterpret_cast<const char*>(packed.data()), packed_size);
  }
  std::string out(reinterpret_cast<const char*>(header.data()), header.size() * sizeof(std::uint64_t));
  return out + body;
}

VtkSeries::VtkSeries(std::filesystem::path directory, std::string basename)
    : dir_(std::move(directory)), pvd_(dir_ / (basename + ".pvd")), base_(std::move(basename)) {}

void VtkSeries::write(const Grid& grid, double time, const std::vector<CellData>& data) {
  int rank;
  MPI_Comm_rank(grid.comm(), &rank);
  if (rank != 0) return;
  const std::string name = fmt::format("{}_{:05d}.vtr", base_, entries_.size());
  const int nx = grid.nx(), ny = grid.ny(), nz = grid.nz();
  // A planar mesh is one sheet of cells at z = 0, as ParaView shows a 2D grid; a mesh of several
  // layers has its z faces. The cell data are in natural order, x fastest, as VTK's.
  const int z_cells = grid.dimension() == 3 ? nz : 0;
  // The cell data go compressed into the appended section; the coordinates and the time stay text.
  std::vector<std::string> packed;
  packed.reserve(data.size());
  for (const auto& d : data) packed.push_back(vtk_compressed_array(d.values));
  write_file_atomically(dir_ / name, [&](std::ostream& out) {
    fmt::print(out, "<?xml version=\"1.0\"?>\n<VTKFile type=\"RectilinearGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
                    "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n");
    fmt::print(out, "<RectilinearGrid WholeExtent=\"0 {} 0 {} 0 {}\">\n", nx, ny, z_cells);
    // The time belongs to the data set, before its pieces: VTK's readers look for it there only.
    fmt::print(out, "<FieldData><DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">{:.17g}</DataArray></FieldData>\n", time);
    fmt::print(out, "<Piece Extent=\"0 {} 0 {} 0 {}\">\n", nx, ny, z_cells);
    fmt::print(out, "<Coordinates>\n<DataArray type=\"Float64\" Name=\"x\" format=\"ascii\">\n");
    for (int i = 0; i < nx; ++i) fmt::print(out, "{:.12g} ", grid.xc(i) - 0.5 * grid.dx(i));
    fmt::print(out, "{:.12g}\n</DataArray>\n<DataArray type=\"Float64\" Name=\"y\" format=\"ascii\">\n", grid.xf(nx - 1));
    for (int j = 0; j < ny; ++j) fmt::print(out, "{:.12g} ", grid.yc(j) - 0.5 * grid.dy(j));
    fmt::print(out, "{:.12g}\n</DataArray>\n", grid.yf(ny - 1));
    if (z_cells == 0) {
      fmt::print(out, "<DataArray type=\"Float64\" Name=\"z\" format=\"ascii\">0</DataArray>\n</Coordinates>\n");
    } else {
      fmt::print(out, "<DataArray type=\"Float64\" Name=\"z\" format=\"ascii\">\n");
      for (int k = 0; k < nz; ++k) fmt::print(out, "{:.12g} ", grid.zc(k) - 0.5 * grid.dz(k));
      fmt::print(out, "{:.12g}\n</DataArray>\n</Coordinates>\n", grid.zf(nz - 1));
    }
    fmt::print(out, "<CellData>\n");
    std::size_t offset = 0;
    for (std::size_t k = 0; k < data.size(); ++k) {
      fmt::print(out, "<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" offset=\"{}\"/>\n",
                 data[k].name, data[k].components, offset);
      offset += packed[k].size();
    }
    fmt::print(out, "</CellData>\n</Piece>\n</RectilinearGrid>\n<AppendedData encoding=\"raw\">\n_");
    for (const auto& p : packed) out.write(p.data(), static_cast<std::streamsize>(p.size()));
    fmt::print(out, "\n</AppendedData>\n</VTKFile>\n");
  });
  entries_.emplace_back(time, name);
  write_file_atomically(pvd_, [&](std::ostream& out) {
    fmt::print(out, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n");
    for (const auto& [t, f] : entries_) fmt::print(out, "<DataSet timestep=\"{:.12g}\" file=\"{}\"/>\n", t, f);
    fmt::print(out, "</Collection>\n</VTKFile>\n");
  });
}

}  // namespace granflow
