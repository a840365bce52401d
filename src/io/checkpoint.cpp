#include "io/checkpoint.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>

#include "io/atomic_file.hpp"
#include "io/collective_failure.hpp"

namespace granflow {

namespace {

// The names of a checkpoint's list of fields, which separates them by spaces.
std::vector<std::string> field_name_list(const std::string& field_names) {
  std::vector<std::string> names;
  for (std::size_t k = 0, end; k < field_names.size(); k = end + 1) {
    end = std::min(field_names.find(' ', k), field_names.size());
    if (end > k) names.push_back(field_names.substr(k, end - k));
  }
  return names;
}

// A checkpoint's field names split into the soil materials' shares (share_NAME: the materials, by
// name) and the rest (the numerics'), each space-separated as the list is.
std::pair<std::string, std::string> materials_and_other_fields(const std::string& field_names) {
  std::string materials, rest;
  for (const std::string& name : field_name_list(field_names)) {
    std::string& to = name.starts_with("share_") ? materials : rest;
    to += (to.empty() ? "" : " ") + (&to == &materials ? name.substr(6) : name);
  }
  return {materials, rest};
}

// The format's version is the magic's last character: "GRNFCKT3" since the fields are one file over
// the whole mesh; version 2 held one file per rank, version 1 a history without the side forces.
constexpr std::uint64_t magic = 0x33544b43464e5247ull;  // "GRNFCKT3"
constexpr std::uint64_t magic_version_1 = 0x31544b43464e5247ull;
// The same format on a mesh of layers, whose header adds nz.
constexpr std::uint64_t magic_layers = 0x334c4b43464e5247ull;  // "GRNFCKL3"

// fields.bin: this header; then each field as (nx + 2 ghosts) x (ny + 2 ghosts) doubles in rows of
// constant j, the ghost cells beyond the mesh's sides included (they hold boundary values and the
// blocked cells' mirrors), on a mesh of layers (nz + 2 ghosts) such planes of constant k; then, rank
// by rank, the `shared` and `summed` numbers of the ranks that wrote it.
struct FieldsHeader {
  std::uint64_t magic;
  std::int64_t nx, ny, ghosts, fields, ranks, shared, summed;
  std::int64_t nz = 1;  // in the file only on a mesh of layers (magic_layers), after the rest
};
// The header's words in the file: 8, or 9 on a mesh of layers.
std::uint64_t header_words(const FieldsHeader& h) { return h.magic == magic_layers ? 9 : 8; }
int header_bytes(const FieldsHeader& h) { return int(header_words(h) * sizeof(std::uint64_t)); }
// The ghosted mesh's extent along each axis: one layer has no ghosts along z.
std::array<std::int64_t, 3> full_extent(const FieldsHeader& h) {
  return {h.nx + 2 * h.ghosts, h.ny + 2 * h.ghosts, h.nz == 1 ? 1 : h.nz + 2 * h.ghosts};
}

constexpr const char* fields_file = "fields.bin";

// Checksums, written on run.txt's last line, so that a restart refuses a checkpoint altered after it
// was written even where every value is one a run could hold (or whose two files come from
// different checkpoints). The fields file's is a sum, modulo 2^64, of a hash of each value's bits
// and its place in the file: the ranks add their parts in any order, and a restart on another number
// of ranks gets the same sum. run.txt's is FNV-1a over its text before that line.
std::uint64_t scramble(std::uint64_t x) {  // splitmix64's finaliser
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

template <class T>
std::uint64_t hash_at(std::uint64_t place, T value) {
  static_assert(sizeof(T) == sizeof(std::uint64_t));
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return scramble(bits ^ scramble(place));
}

std::uint64_t text_checksum(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const unsigned char ch : text) h = (h ^ ch) * 0x100000001b3ull;
  return h;
}

std::string other_mesh(const FieldsHeader& h, const std::array<int, 3>& cells) {
  auto counts = [](std::int64_t nx, std::int64_t ny, std::int64_t nz) {
    return nz == 1 ? fmt::format("{} x {}", nx, ny) : fmt::format("{} x {} x {}", nx, ny, nz);
  };
  return fmt::format("the checkpoint is of a {} mesh, the case has {} cells", counts(h.nx, h.ny, h.nz),
                     counts(cells[0], cells[1], cells[2]));
}
bool same_mesh(const FieldsHeader& h, const std::array<int, 3>& cells) {
  return h.nx == cells[0] && h.ny == cells[1] && h.nz == cells[2];
}

// The header alone, where the file has one.
std::optional<FieldsHeader> read_header(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  FieldsHeader h{};
  if (!in.read(reinterpret_cast<char*>(&h), 8 * sizeof(std::uint64_t)) || (h.magic != magic && h.magic != magic_layers))
    return std::nullopt;
  if (h.magic == magic_layers && !in.read(reinterpret_cast<char*>(&h.nz), sizeof h.nz)) return std::nullopt;
  return h;
}

// This rank's box of the whole ghosted mesh, in its coordinates (cell i at i + ghosts): `window` is
// what its local vectors hold, `own` what it writes (its cells, and the ghosts beyond the mesh's sides
// it touches), so that the ranks together write every value once. One layer: z0 = 0, depth 1.
struct Box {
  int x0, y0, z0, width, height, depth;
  std::size_t values() const { return std::size_t(width) * std::size_t(height) * std::size_t(depth); }
};
struct RankLayout {
  int full_x, full_y, full_z;  // the whole ghosted mesh
  Box window, own;
  // The start, in a local array of `window`, of row (y, z) of `own`.
  std::size_t own_row_in_window(int y, int z) const {
    return (std::size_t(own.z0 - window.z0 + z) * std::size_t(window.height) + std::size_t(own.y0 - window.y0 + y)) *
               std::size_t(window.width) +
           std::size_t(own.x0 - window.x0);
  }
};

RankLayout rank_layout(DM dm, const std::array<int, 3>& cells) {
  PetscInt xs, ys, zs, xm, ym, zm, gxs, gys, gzs, gxm, gym, gzm, g;
  PetscCallAbort(PETSC_COMM_WORLD, DMDAGetCorners(dm, &xs, &ys, &zs, &xm, &ym, &zm));
  PetscCallAbort(PETSC_COMM_WORLD, DMDAGetGhostCorners(dm, &gxs, &gys, &gzs, &gxm, &gym, &gzm));
  PetscCallAbort(PETSC_COMM_WORLD, DMDAGetInfo(dm, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, &g, nullptr, nullptr,
                                   nullptr, nullptr));
  const int w = int(g), wz = cells[2] == 1 ? 0 : w;  // one layer has no ghosts along z
  const int nx = cells[0], ny = cells[1], nz = cells[2];
  const int x0 = xs == 0 ? 0 : int(xs) + w, x1 = xs + xm == nx ? nx + 2 * w : int(xs + xm) + w;
  const int y0 = ys == 0 ? 0 : int(ys) + w, y1 = ys + ym == ny ? ny + 2 * w : int(ys + ym) + w;
  const int z0 = zs == 0 ? 0 : int(zs) + wz, z1 = zs + zm == nz ? nz + 2 * wz : int(zs + zm) + wz;
  return {nx + 2 * w,
          ny + 2 * w,
          nz + 2 * wz,
          {int(gxs) + w, int(gys) + w, int(gzs) + wz, int(gxm), int(gym), int(gzm)},
          {x0, y0, z0, x1 - x0, y1 - y0, z1 - z0}};
}

// A box of a row-major array of full_x x full_y x full_z doubles, as an MPI datatype.
struct Subarray {
  MPI_Datatype type = MPI_DATATYPE_NULL;
  Subarray(int full_x, int full_y, int full_z, const Box& r) {
    const int sizes[3] = {full_z, full_y, full_x}, sub[3] = {r.depth, r.height, r.width}, starts[3] = {r.z0, r.y0, r.x0};
    MPI_Type_create_subarray(3, sizes, sub, starts, MPI_ORDER_C, MPI_DOUBLE, &type);
    MPI_Type_commit(&type);
  }
  ~Subarray() { MPI_Type_free(&type); }
  Subarray(const Subarray&) = delete;
  Subarray& operator=(const Subarray&) = delete;
};

// An MPI-IO file, closed on every path out. Errors come back as text ("" if none), the same on
// every rank, since each call below is collective.
class MpiFile {
 public:
  MpiFile(MPI_Comm comm, const std::filesystem::path& path, int mode) : comm_(comm), path_(path) {
    agreed(MPI_File_open(comm, path.c_str(), mode, MPI_INFO_NULL, &file_), "open");
    open_ = problem_.empty();
  }
  ~MpiFile() {
    if (open_) MPI_File_close(&file_);
  }
  MpiFile(const MpiFile&) = delete;
  MpiFile& operator=(const MpiFile&) = delete;
  const std::string& problem() const { return problem_; }
  MPI_File get() const { return file_; }
  // Records the first failure of a collective step, on every rank.
  void agreed(int code, const char* what) {
    std::string mine;
    if (code != MPI_SUCCESS) {
      char text[MPI_MAX_ERROR_STRING];
      int length = 0;
      MPI_Error_string(code, text, &length);
      mine = fmt::format("cannot {} {}: {}", what, path_.string(), std::string(text, size_t(length)));
    }
    if (auto first = first_failure(comm_, mine); problem_.empty()) problem_ = std::move(first);
  }

 private:
  MPI_Comm comm_;
  std::filesystem::path path_;
  MPI_File file_ = MPI_FILE_NULL;
  bool open_ = false;
  std::string problem_;
};

MPI_Offset field_offset(const FieldsHeader& h, std::int64_t k) {
  const auto full = full_extent(h);
  return MPI_Offset(header_bytes(h)) + MPI_Offset(sizeof(double)) * full[0] * full[1] * full[2] * k;
}

// This rank's part of the fields file's checksum: the header (on rank 0), the rows of numbers
// `rows` holds, from rank `first_rank`'s on, and the values of the fields this rank writes (`own`),
// from its local vectors.
std::uint64_t checksum_part(MPI_Comm comm, const FieldsHeader& h, std::span<Field* const> fields, std::int64_t first_rank,
                            std::span<const double> rows) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  std::uint64_t sum = 0;
  const std::uint64_t words = header_words(h);
  if (rank == 0) {
    const std::int64_t counts[] = {h.nx, h.ny, h.ghosts, h.fields, h.ranks, h.shared, h.summed, h.nz};
    sum += hash_at(0, h.magic);
    for (std::uint64_t w = 0; w + 1 < words; ++w) sum += hash_at(1 + w, counts[w]);
  }
  const auto extent = full_extent(h);
  const std::uint64_t full_x = std::uint64_t(extent[0]), full_y = std::uint64_t(extent[1]),
                      full = full_x * full_y * std::uint64_t(extent[2]);
  const std::uint64_t first_row = words + full * std::uint64_t(h.fields) +
                                  std::uint64_t(first_rank) * std::uint64_t(h.shared + h.summed);
  for (std::size_t s = 0; s < rows.size(); ++s) sum += hash_at(first_row + s, rows[s]);
  if (fields.empty()) return sum;
  const RankLayout l = rank_layout(fields[0]->dm(), {int(h.nx), int(h.ny), int(h.nz)});
  for (std::size_t k = 0; k < fields.size(); ++k) {
    const PetscScalar* a;
    PetscCallAbort(PETSC_COMM_WORLD, VecGetArrayRead(fields[k]->local(), &a));
    for (int z = 0; z < l.own.depth; ++z)
      for (int y = 0; y < l.own.height; ++y) {
        const PetscScalar* line = a + l.own_row_in_window(y, z);
        const std::uint64_t place = words + full * k +
                                    (std::uint64_t(l.own.z0 + z) * full_y + std::uint64_t(l.own.y0 + y)) * full_x +
                                    std::uint64_t(l.own.x0);
        for (int x = 0; x < l.own.width; ++x) sum += hash_at(place + std::uint64_t(x), line[x]);
      }
    PetscCallAbort(PETSC_COMM_WORLD, VecRestoreArrayRead(fields[k]->local(), &a));
  }
  return sum;
}

std::uint64_t summed_over_ranks(MPI_Comm comm, std::uint64_t part) {
  std::uint64_t total = 0;
  MPI_Allreduce(&part, &total, 1, MPI_UINT64_T, MPI_SUM, comm);
  return total;
}

// Writes the header, each rank's row of numbers and the fields.
std::string send_fields(MPI_Comm comm, const std::filesystem::path& path, const FieldsHeader& h,
                        std::span<Field* const> fields, const std::vector<double>& row) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  MpiFile file(comm, path, MPI_MODE_WRONLY | MPI_MODE_CREATE);
  if (!file.problem().empty()) return file.problem();
  MPI_Status status;
  file.agreed(rank == 0 ? MPI_File_write_at(file.get(), 0, &h, header_bytes(h), MPI_BYTE, &status) : MPI_SUCCESS, "write");
  const MPI_Offset rows = field_offset(h, h.fields) + MPI_Offset(sizeof(double)) * rank * MPI_Offset(row.size());
  file.agreed(MPI_File_write_at_all(file.get(), rows, row.data(), int(row.size()), MPI_DOUBLE, &status), "write");
  if (!fields.empty()) {
    const RankLayout l = rank_layout(fields[0]->dm(), {int(h.nx), int(h.ny), int(h.nz)});
    const Subarray in_file(l.full_x, l.full_y, l.full_z, l.own);
    const Box own_in_window{l.own.x0 - l.window.x0, l.own.y0 - l.window.y0, l.own.z0 - l.window.z0,
                            l.own.width,           l.own.height,           l.own.depth};
    const Subarray in_memory(l.window.width, l.window.height, l.window.depth, own_in_window);
    for (size_t k = 0; k < fields.size() && file.problem().empty(); ++k) {
      file.agreed(MPI_File_set_view(file.get(), field_offset(h, std::int64_t(k)), MPI_DOUBLE, in_file.type, "native",
                                    MPI_INFO_NULL), "write");
      const PetscScalar* a;
      PetscCallAbort(PETSC_COMM_WORLD, VecGetArrayRead(fields[k]->local(), &a));
      file.agreed(MPI_File_write_all(file.get(), a, 1, in_memory.type, &status), "write");
      PetscCallAbort(PETSC_COMM_WORLD, VecRestoreArrayRead(fields[k]->local(), &a));
    }
  }
  return file.problem();
}

// Reads back what this rank wrote and compares it, to the bit. Open MPI's file layer (ompio, 4.1)
// reports a write that failed part way (a full disk) as a success and leaves a hole of zeros in the
// file, which a restart would read as the state.
std::string verify_fields(MPI_Comm comm, const std::filesystem::path& path, const FieldsHeader& h,
                          std::span<Field* const> fields, const std::vector<double>& row) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  MpiFile file(comm, path, MPI_MODE_RDONLY);
  if (!file.problem().empty()) return file.problem();
  MPI_Status status;
  bool same = true;
  FieldsHeader read_back{};
  file.agreed(rank == 0 ? MPI_File_read_at(file.get(), 0, &read_back, header_bytes(h), MPI_BYTE, &status) : MPI_SUCCESS,
              "read back");
  if (rank == 0) same = std::memcmp(&read_back, &h, size_t(header_bytes(h))) == 0;
  std::vector<double> buffer(row.size());
  const MPI_Offset rows = field_offset(h, h.fields) + MPI_Offset(sizeof(double)) * rank * MPI_Offset(row.size());
  file.agreed(MPI_File_read_at_all(file.get(), rows, buffer.data(), int(buffer.size()), MPI_DOUBLE, &status), "read back");
  same = same && std::memcmp(buffer.data(), row.data(), row.size() * sizeof(double)) == 0;
  if (!fields.empty()) {
    const RankLayout l = rank_layout(fields[0]->dm(), {int(h.nx), int(h.ny), int(h.nz)});
    const Subarray in_file(l.full_x, l.full_y, l.full_z, l.own);
    buffer.resize(l.own.values());
    for (size_t k = 0; k < fields.size() && file.problem().empty(); ++k) {
      file.agreed(MPI_File_set_view(file.get(), field_offset(h, std::int64_t(k)), MPI_DOUBLE, in_file.type, "native",
                                    MPI_INFO_NULL), "read back");
      file.agreed(MPI_File_read_all(file.get(), buffer.data(), int(buffer.size()), MPI_DOUBLE, &status), "read back");
      const PetscScalar* a;
      PetscCallAbort(PETSC_COMM_WORLD, VecGetArrayRead(fields[k]->local(), &a));
      for (int z = 0; z < l.own.depth && same; ++z)
        for (int y = 0; y < l.own.height && same; ++y) {
          const PetscScalar* line = a + l.own_row_in_window(y, z);
          const size_t row = size_t(z) * size_t(l.own.height) + size_t(y);
          same = std::memcmp(line, buffer.data() + row * size_t(l.own.width), size_t(l.own.width) * sizeof(double)) == 0;
        }
      PetscCallAbort(PETSC_COMM_WORLD, VecRestoreArrayRead(fields[k]->local(), &a));
    }
  }
  if (!file.problem().empty()) return file.problem();
  int all_same = same ? 1 : 0, agreed = 0;
  MPI_Allreduce(&all_same, &agreed, 1, MPI_INT, MPI_MIN, comm);
  if (agreed) return {};
  return fmt::format("cannot write {}: what it holds is not what was written (is the disk full?)", path.string());
}

// `row`: this rank's shared numbers, then its summed ones.
std::string write_fields(MPI_Comm comm, const std::filesystem::path& path, const FieldsHeader& h,
                         std::span<Field* const> fields, const std::vector<double>& row) {
  if (auto problem = send_fields(comm, path, h, fields, row); !problem.empty()) return problem;
  return verify_fields(comm, path, h, fields, row);  // the file closed: what it holds is on its way to the disk
}

// Reads the fields and this rank's scalars, and the file's checksum (checksum_part) into `checksum`;
// returns an empty string or what is wrong (the same on every rank).
std::string read_fields(MPI_Comm comm, const std::filesystem::path& path, const std::array<int, 3>& cells,
                        std::span<Field* const> fields, CheckpointScalars& scalars, std::uint64_t& checksum) {
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  MpiFile file(comm, path, MPI_MODE_RDONLY);
  if (!file.problem().empty()) return file.problem();
  FieldsHeader h{};
  MPI_Status status;
  MPI_Offset bytes = 0;
  file.agreed(MPI_File_get_size(file.get(), &bytes), "read");
  // The planar header's 8 words, and a mesh of layers' ninth where the file is long enough to hold it.
  const int header_read = bytes >= MPI_Offset(9 * sizeof(std::uint64_t)) ? 9 : 8;
  file.agreed(MPI_File_read_at_all(file.get(), 0, &h, header_read * int(sizeof(std::uint64_t)), MPI_BYTE, &status), "read");
  if (!file.problem().empty()) return file.problem();
  if (h.magic != magic_layers) h.nz = 1;
  if (bytes < MPI_Offset(header_bytes(h)) || (h.magic != magic && h.magic != magic_layers) ||
      (h.magic == magic_layers && h.nz < 2))
    return fmt::format("{} is not a granflow checkpoint", path.string());
  if (!same_mesh(h, cells)) return other_mesh(h, cells);
  if (h.fields != std::int64_t(fields.size()))
    return fmt::format("the checkpoint holds {} fields, this case needs {} (a different model or numerics)", h.fields,
                       fields.size());
  // Bounded before they are multiplied: a damaged header must not overflow the size check.
  constexpr std::int64_t most = 1 << 24;
  if (h.ranks < 1 || h.ranks > most || h.shared < 0 || h.shared > most || h.summed < 0 || h.summed > most)
    return fmt::format("{} is damaged (its header counts {} ranks, {} and {} numbers)", path.string(), h.ranks,
                       h.shared, h.summed);
  const std::int64_t width = h.shared + h.summed;
  if (h.ghosts != Grid::ghost_width ||
      bytes != field_offset(h, h.fields) + MPI_Offset(sizeof(double)) * h.ranks * width)
    return fmt::format("{} is truncated or damaged (its size does not match its header)", path.string());
  // The numbers: this rank's own where the decomposition is the one written; else the shared ones of
  // the first rank, and the totals of the summed ones on rank 0.
  std::vector<double> table(size_t(h.ranks * width));
  file.agreed(MPI_File_read_at_all(file.get(), field_offset(h, h.fields), table.data(), int(table.size()), MPI_DOUBLE,
                                   &status), "read");
  const double* row = table.data() + (h.ranks == size ? rank * width : 0);
  scalars.shared.assign(row, row + h.shared);
  scalars.summed.assign(row + h.shared, row + width);
  if (h.ranks != size)
    for (std::int64_t s = 0; s < h.summed; ++s) {
      double total = 0.0;
      for (std::int64_t r = 0; r < h.ranks; ++r) total += table[size_t(r * width + h.shared + s)];
      scalars.summed[size_t(s)] = rank == 0 ? total : 0.0;
    }
  if (!fields.empty()) {
    const RankLayout l = rank_layout(fields[0]->dm(), cells);
    const Subarray in_file(l.full_x, l.full_y, l.full_z, l.window);
    for (size_t k = 0; k < fields.size() && file.problem().empty(); ++k) {
      file.agreed(MPI_File_set_view(file.get(), field_offset(h, std::int64_t(k)), MPI_DOUBLE, in_file.type, "native",
                                    MPI_INFO_NULL), "read");
      PetscScalar* a;
      PetscCallAbort(PETSC_COMM_WORLD, VecGetArray(fields[k]->local(), &a));
      file.agreed(MPI_File_read_all(file.get(), a, int(l.window.values()), MPI_DOUBLE, &status), "read");
      PetscCallAbort(PETSC_COMM_WORLD, VecRestoreArray(fields[k]->local(), &a));
      fields[k]->gather_from_local();
    }
  }
  if (!file.problem().empty()) return file.problem();
  checksum = summed_over_ranks(comm, checksum_part(comm, h, fields, 0, rank == 0 ? std::span<const double>(table)
                                                                                   : std::span<const double>()));
  return {};
}

// The first value of this rank's cells or of the numbers that is NaN or infinite, named ("" if none).
// No run writes one: a step that makes one fails and is taken again or ends the run first. So such a
// value is damage done to the file after it was written, and a restart from it would fail later, in a
// solve, where the cause no longer shows.
std::string non_finite_value(std::span<Field* const> fields, const std::string& field_names,
                             const CheckpointScalars& scalars) {
  const std::vector<std::string> names = field_name_list(field_names);
  for (std::size_t k = 0; k < fields.size(); ++k) {
    PetscInt xs, ys, zs, xm, ym, zm;
    PetscCallAbort(PETSC_COMM_WORLD, DMDAGetCorners(fields[k]->dm(), &xs, &ys, &zs, &xm, &ym, &zm));
    const ConstFieldArray a(fields[k]->dm(), fields[k]->global());
    const auto name = names.size() == fields.size() ? names[k] : std::to_string(k);
    for (PetscInt z = zs; z < zs + zm; ++z)
      for (PetscInt j = ys; j < ys + ym; ++j)
        for (PetscInt i = xs; i < xs + xm; ++i)
          if (const double v = a.volume()[z][j][i]; !std::isfinite(v))
            return zm == 1 && zs == 0 ? fmt::format("the checkpoint is damaged: its field {} holds {} in cell ({}, {})", name, v, i, j)
                                      : fmt::format("the checkpoint is damaged: its field {} holds {} in cell ({}, {}, {})", name,
                                                    v, i, j, z);
  }
  for (const auto* numbers : {&scalars.shared, &scalars.summed})
    for (const double x : *numbers)
      if (!std::isfinite(x)) return fmt::format("the checkpoint is damaged: one of its numbers is {}", x);
  return {};
}

constexpr std::string_view checksum_line = "\nchecksum ", checksum_key = checksum_line.substr(1);

void write_run(const std::filesystem::path& path, const RunCheckpoint& r, std::uint64_t fields_checksum) {
  fmt::memory_buffer text;
  auto out = std::back_inserter(text);
  fmt::format_to(out, "time {:a}\nnext_dt {:a}\noutput_index {}\ndissipated_energy {:a}\ninitial_soil_volume {:a}\n", r.time,
                 r.next_dt, r.output_index, r.dissipated_energy, r.initial_soil_volume);
  fmt::format_to(out, "series {}\n", r.series.size());
  for (const auto& [t, f] : r.series) fmt::format_to(out, "{:a} {}\n", t, f);
  fmt::format_to(out, "history {}\n", r.history.size());
  for (const auto& row : r.history) fmt::format_to(out, "{}\n", row);
  fmt::format_to(out, "domain {}\nsteps {}\nphysics {}\nfields {}\nboundaries {}\nboundary_work {:a}\n", r.domain,
                 r.steps, r.physics, r.fields, r.boundaries, r.boundary_work);
  const std::string_view body(text.data(), text.size());
  write_file_atomically(path, [&](std::ostream& file) {
    file << body;
    fmt::print(file, "{}{:016x} {:016x}\n", checksum_key, fields_checksum, text_checksum(body));
  });
}

// A number as write_run prints it (hexadecimal floating point); NaN if the text is not one, which
// the checks of the clock then refuse.
double hex_double(const std::string& s) {
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  return end == s.c_str() || *end != '\0' ? std::nan("") : x;
}

// `fields_checksum` receives the fields file's checksum where run.txt gives one (older checkpoints do not).
RunCheckpoint read_run(const std::filesystem::path& path, std::optional<std::uint64_t>& fields_checksum) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw CheckpointError(fmt::format("cannot read {}", path.string()));
  std::string content{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  // Every run.txt ends its last line; one that does not was cut short (perhaps in its checksum line).
  if (!content.empty() && content.back() != '\n') throw CheckpointError(fmt::format("{} is truncated", path.string()));
  // The checksum line is the last; its text checksum covers every byte before it. It is compared
  // once the text has been read, so that a value that is not one (a count of 'abc') is named first.
  bool text_matches = true;
  if (const size_t at = content.rfind(checksum_line); at != std::string::npos) {
    const std::string line = content.substr(at + checksum_line.size());
    std::uint64_t fields_sum = 0, text_sum = 0;
    char tail = '\0';
    const bool read = std::sscanf(line.c_str(), "%16" SCNx64 " %16" SCNx64 "%c", &fields_sum, &text_sum, &tail) == 3 &&
                      tail == '\n' && line.find('\n') + 1 == line.size();
    content.resize(at + 1);
    text_matches = read && text_sum == text_checksum(content);
    fields_checksum = fields_sum;
  }
  std::istringstream in(content);
  RunCheckpoint r;
  std::string key, value;
  auto field = [&](const char* name) {
    if (!(in >> key >> value) || key != name) throw CheckpointError(fmt::format("{}: expected '{}'", path.string(), name));
    return value;
  };
  auto count_in = [&](const char* name, const std::string& text, long long most = std::numeric_limits<int>::max()) {
    char* end = nullptr;
    errno = 0;
    const long long n = std::strtoll(text.c_str(), &end, 10);
    if (end == text.c_str() || *end != '\0' || errno == ERANGE || n < 0 || n > most)
      throw CheckpointError(fmt::format("{}: '{}' is not a count for '{}'", path.string(), text, name));
    return size_t(n);
  };
  auto count = [&](const char* name) { return count_in(name, field(name)); };
  r.time = hex_double(field("time"));
  r.next_dt = hex_double(field("next_dt"));
  r.output_index = int(count("output_index"));
  r.dissipated_energy = hex_double(field("dissipated_energy"));
  r.initial_soil_volume = hex_double(field("initial_soil_volume"));
  if (!(std::isfinite(r.time) && r.time >= 0.0 && std::isfinite(r.next_dt) && r.next_dt > 0.0 && r.output_index >= 0 &&
        std::isfinite(r.dissipated_energy) && std::isfinite(r.initial_soil_volume)))
    throw CheckpointError(fmt::format("{}: the clock (time {}, next_dt {}, output_index {}) is not a run's",
                                      path.string(), r.time, r.next_dt, r.output_index));
  const size_t n_series = count("series");
  for (size_t k = 0; k < n_series; ++k) {
    std::string t, f;
    if (!(in >> t >> f)) throw CheckpointError(fmt::format("{} is truncated", path.string()));
    if (!std::isfinite(hex_double(t)))
      throw CheckpointError(fmt::format("{}: '{}' is not the time of an output", path.string(), t));
    r.series.emplace_back(hex_double(t), f);
  }
  const size_t n_history = count("history");
  std::string line;
  std::getline(in, line);  // end of the count's line
  for (size_t k = 0; k < n_history; ++k) {
    if (!std::getline(in, line)) throw CheckpointError(fmt::format("{} is truncated", path.string()));
    r.history.push_back(line);
  }
  // Added later, one "key value" line each: older checkpoints end with the history.
  while (std::getline(in, line)) {
    const size_t space = line.find(' ');
    const std::string name = line.substr(0, space), text = space == std::string::npos ? "" : line.substr(space + 1);
    if (name == "domain") r.domain = text;
    else if (name == "steps") r.steps = long(count_in("steps", text, std::numeric_limits<long>::max()));
    else if (name == "physics") r.physics = text;
    else if (name == "fields") r.fields = text;
    else if (name == "boundaries") r.boundaries = text;
    else if (name == "boundary_work") {
      r.boundary_work = hex_double(text);
      if (!std::isfinite(r.boundary_work))
        throw CheckpointError(
            fmt::format("{}: '{}' is not the energy brought in through the sides", path.string(), text));
    }
  }
  if (!text_matches)
    throw CheckpointError(fmt::format("{} does not match its checksum (altered after it was written)", path.string()));
  return r;
}

// Every rank throws if any rank failed, with the same message.
void agree(MPI_Comm comm, const std::string& mine) {
  if (auto text = first_failure(comm, mine); !text.empty()) throw CheckpointError(text);
}

}  // namespace

void write_checkpoint(MPI_Comm comm, const std::filesystem::path& dir, const std::array<int, 3>& cells,
                      const RunCheckpoint& run, std::span<Field* const> fields, const CheckpointScalars& scalars) {
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  // What rank 0 does alone; its failure (a full disk) reaches every rank, which would otherwise wait
  // for it in the next collective call.
  auto on_rank_0 = [&](auto&& step) {
    std::string problem;
    if (rank == 0) {
      try {
        step();
      } catch (const std::exception& e) {
        problem = e.what();
      }
    }
    if (auto text = first_failure(comm, problem); !text.empty()) throw std::runtime_error(text);
  };
  const auto partial = dir / "checkpoint.partial", final_dir = dir / "checkpoint", old = dir / "checkpoint.old";
  on_rank_0([&] {
    std::filesystem::remove_all(partial);
    std::filesystem::create_directories(partial);
  });
  const FieldsHeader h{cells[2] == 1 ? magic : magic_layers,
                       cells[0],
                       cells[1],
                       Grid::ghost_width,
                       std::int64_t(fields.size()),
                       size,
                       std::int64_t(scalars.shared.size()),
                       std::int64_t(scalars.summed.size()),
                       cells[2]};
  std::vector<double> row = scalars.shared;
  row.insert(row.end(), scalars.summed.begin(), scalars.summed.end());
  if (auto problem = write_fields(comm, partial / fields_file, h, fields, row); !problem.empty())
    throw std::runtime_error(problem);
  const std::uint64_t checksum = summed_over_ranks(comm, checksum_part(comm, h, fields, rank, row));
  on_rank_0([&] { write_run(partial / "run.txt", run, checksum); });
  on_rank_0([&] {
    // The last complete checkpoint is kept until the new one has its name: it is checkpoint/, or,
    // after a run killed between these renames, checkpoint.old/ alone, which must then not be
    // removed before the new one is in place.
    if (std::filesystem::exists(final_dir)) {
      std::filesystem::remove_all(old);
      std::filesystem::rename(final_dir, old);
    }
    std::filesystem::rename(partial, final_dir);
    std::filesystem::remove_all(old);
  });
}

RunCheckpoint read_checkpoint(MPI_Comm comm, const std::filesystem::path& dir, const std::array<int, 3>& cells,
                              const std::string& domain, const std::string& field_names,
                              std::span<Field* const> fields, CheckpointScalars& scalars) {
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  // A run killed between the two renames of write_checkpoint leaves only checkpoint.old.
  auto from = dir / "checkpoint";
  if (!std::filesystem::exists(from / "run.txt") && std::filesystem::exists(dir / "checkpoint.old" / "run.txt"))
    from = dir / "checkpoint.old";
  std::string problem;
  if (!std::filesystem::exists(from / "run.txt"))
    problem = fmt::format("no checkpoint to restart from in {} (one is written at each output time after the start)", dir.string());
  agree(comm, problem);
  RunCheckpoint run;
  std::optional<std::uint64_t> recorded_checksum;
  if (rank == 0) {
    try {
      run = read_run(from / "run.txt", recorded_checksum);
    } catch (const CheckpointError& e) {
      problem = fmt::format("the checkpoint is damaged: {}", e.what());
    } catch (const std::exception& e) {  // whatever else reading it throws must reach every rank too
      problem = fmt::format("the checkpoint is damaged: {}: {}", (from / "run.txt").string(), e.what());
    }
    if (problem.empty() && !run.domain.empty() && run.domain != domain) {
      // Another mesh blocks other cells of the same obstacles: name the mesh, the cause.
      const auto h = read_header(from / fields_file);
      problem = h && !same_mesh(*h, cells)
                    ? other_mesh(*h, cells)
                    : fmt::format("the checkpoint is of the domain {}; the case's is {}", run.domain, domain);
    }
    // Other numerics may keep as many fields, of other meanings (cell forces where the look-ahead
    // keeps the last step's velocity): the names tell.
    // The mass a cell's momentum is carried with is kept only where the step reads it (numerics.density_jump).
    auto without_carried = [](std::string names) {
      constexpr std::string_view carried = " carried_density";
      if (const auto at = names.find(carried); at != std::string::npos) names.erase(at, carried.size());
      return names;
    };
    if (problem.empty() && !run.fields.empty() && run.fields != field_names &&
        without_carried(run.fields) == without_carried(field_names)) {
      problem = run.fields.size() < field_names.size()
                    ? "the checkpoint's run started each step at the carried velocity where the mixture's density "
                      "jumps (written before numerics.density_jump = \"keep_kinetic_energy\" became the default, or "
                      "with \"keep_velocity\"); restart it with --set numerics.density_jump=keep_velocity"
                    : "the checkpoint's run kept the kinetic energy a cell's momentum was carried with "
                      "(numerics.density_jump = \"keep_kinetic_energy\"); restart it with that";
    }
    if (problem.empty() && !run.fields.empty() && run.fields != field_names) {
      const auto [had, had_rest] = materials_and_other_fields(run.fields);
      const auto [has, has_rest] = materials_and_other_fields(field_names);
      problem = had_rest == has_rest
                    ? fmt::format("the checkpoint's run had other soil materials ({}) than the case has ({}); a restart "
                                  "goes on with the materials it stopped with",
                                  had.empty() ? "none besides the rheology's soil" : had,
                                  has.empty() ? "none besides the rheology's soil" : has)
                    : fmt::format("the checkpoint holds the fields of other numerics ({}); this case's are {}",
                                  run.fields, field_names);
    }
  }
  agree(comm, problem);
  if (!std::filesystem::exists(from / fields_file) && std::filesystem::exists(from / "rank_0.bin")) {
    std::uint64_t first = 0;
    std::ifstream(from / "rank_0.bin", std::ios::binary).read(reinterpret_cast<char*>(&first), sizeof first);
    problem = fmt::format("{} was written by an earlier version of granflow (checkpoint format {}, one file per rank); "
                          "run the case anew", from.string(), first == magic_version_1 ? 1 : 2);
  }
  agree(comm, problem);
  std::uint64_t checksum = 0;
  agree(comm, read_fields(comm, from / fields_file, cells, fields, scalars, checksum));
  agree(comm, non_finite_value(fields, field_names, scalars));
  std::uint64_t recorded[2] = {recorded_checksum.has_value(), recorded_checksum.value_or(0)};
  MPI_Bcast(recorded, 2, MPI_UINT64_T, 0, comm);
  if (recorded[0] && recorded[1] != checksum)
    agree(comm, fmt::format("the checkpoint is damaged: {} does not match the checksum in run.txt (altered after it was "
                            "written, or of another checkpoint)", (from / fields_file).string()));
  double clock[7] = {run.time, run.next_dt, double(run.output_index), run.dissipated_energy, run.initial_soil_volume,
                     double(run.steps), run.boundary_work};
  MPI_Bcast(clock, 7, MPI_DOUBLE, 0, comm);
  run.time = clock[0];
  run.next_dt = clock[1];
  run.output_index = int(clock[2]);
  run.dissipated_energy = clock[3];
  run.initial_soil_volume = clock[4];
  run.steps = long(clock[5]);
  run.boundary_work = clock[6];
  return run;
}

}  // namespace granflow
