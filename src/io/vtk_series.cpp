#include "io/vtk_series.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "io/atomic_file.hpp"

namespace granflow {

VtkSeries::VtkSeries(std::filesystem::path directory, std::string basename)
    : dir_(std::move(directory)), pvd_(dir_ / (basename + ".pvd")), base_(std::move(basename)) {}

void VtkSeries::write(const Grid& grid, double time, const std::vector<CellData>& data) {
  int rank;
  MPI_Comm_rank(grid.comm(), &rank);
  if (rank != 0) return;
  const std::string name = fmt::format("{}_{:05d}.vtr", base_, entries_.size());
  const int nx = grid.nx(), ny = grid.ny();
  write_file_atomically(dir_ / name, [&](std::ostream& out) {
    fmt::print(out, "<?xml version=\"1.0\"?>\n<VTKFile type=\"RectilinearGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
    fmt::print(out, "<RectilinearGrid WholeExtent=\"0 {} 0 {} 0 0\">\n", nx, ny);
    // The time belongs to the data set, before its pieces: VTK's readers look for it there only.
    fmt::print(out, "<FieldData><DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">{:.17g}</DataArray></FieldData>\n", time);
    fmt::print(out, "<Piece Extent=\"0 {} 0 {} 0 0\">\n", nx, ny);
    fmt::print(out, "<Coordinates>\n<DataArray type=\"Float64\" Name=\"x\" format=\"ascii\">\n");
    for (int i = 0; i < nx; ++i) fmt::print(out, "{:.12g} ", grid.xc(i) - 0.5 * grid.dx(i));
    fmt::print(out, "{:.12g}\n</DataArray>\n<DataArray type=\"Float64\" Name=\"y\" format=\"ascii\">\n", grid.xf(nx - 1));
    for (int j = 0; j < ny; ++j) fmt::print(out, "{:.12g} ", grid.yc(j) - 0.5 * grid.dy(j));
    fmt::print(out, "{:.12g}\n</DataArray>\n<DataArray type=\"Float64\" Name=\"z\" format=\"ascii\">0</DataArray>\n</Coordinates>\n", grid.yf(ny - 1));
    fmt::print(out, "<CellData>\n");
    for (const auto& d : data) {
      fmt::print(out, "<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n", d.name, d.components);
      for (size_t k = 0; k < d.values.size(); ++k) fmt::print(out, "{:.9g}{}", d.values[k], (k + 1) % 12 ? " " : "\n");
      fmt::print(out, "\n</DataArray>\n");
    }
    fmt::print(out, "</CellData>\n</Piece>\n</RectilinearGrid>\n</VTKFile>\n");
  });
  entries_.emplace_back(time, name);
  write_file_atomically(pvd_, [&](std::ostream& out) {
    fmt::print(out, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n");
    for (const auto& [t, f] : entries_) fmt::print(out, "<DataSet timestep=\"{:.12g}\" file=\"{}\"/>\n", t, f);
    fmt::print(out, "</Collection>\n</VTKFile>\n");
  });
}

}  // namespace granflow
