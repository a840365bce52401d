#include "io/checkpoint.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <optional>

#include "io/atomic_file.hpp"
#include "io/collective_failure.hpp"

namespace granflow {

namespace {

// The format's version is the magic's last character: "GRNFCKT2" since history.csv holds the
// forces on the sides (a version 1 checkpoint's history rows lack them).
constexpr std::uint64_t magic = 0x32544b43464e5247ull;  // "GRNFCKT2"
constexpr std::uint64_t magic_version_1 = 0x31544b43464e5247ull;

struct RankHeader {
  std::uint64_t magic;
  std::int64_t ranks, rank, nx, ny, fields, scalars;
};

std::filesystem::path rank_file(const std::filesystem::path& d, int rank) { return d / fmt::format("rank_{}.bin", rank); }

void write_rank(const std::filesystem::path& path, const RankHeader& h, std::span<Field* const> fields,
                std::span<const double> scalars) {
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(&h), sizeof h);
    for (Field* f : fields) {
      PetscInt n;
      VecGetLocalSize(f->local(), &n);
      const std::int64_t size = n;
      const PetscScalar* a;
      VecGetArrayRead(f->local(), &a);
      out.write(reinterpret_cast<const char*>(&size), sizeof size);
      out.write(reinterpret_cast<const char*>(a), std::streamsize(sizeof(double) * n));
      VecRestoreArrayRead(f->local(), &a);
    }
    out.write(reinterpret_cast<const char*>(scalars.data()), std::streamsize(sizeof(double) * scalars.size()));
  });
}

std::string other_mesh(std::int64_t nx, std::int64_t ny, std::int64_t case_nx, std::int64_t case_ny) {
  return fmt::format("the checkpoint is of a {} x {} mesh, the case has {} x {} cells", nx, ny, case_nx, case_ny);
}

// The header alone, where the file has one.
std::optional<RankHeader> read_header(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  RankHeader h{};
  if (!in.read(reinterpret_cast<char*>(&h), sizeof h) || h.magic != magic) return std::nullopt;
  return h;
}

// Reads this rank's file; returns an empty string or what is wrong with it.
std::string read_rank(const std::filesystem::path& path, const RankHeader& expected, std::span<Field* const> fields,
                      std::vector<double>& scalars) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return fmt::format("cannot read {}", path.string());
  RankHeader h{};
  in.read(reinterpret_cast<char*>(&h), sizeof h);
  if (in && h.magic == magic_version_1)
    return fmt::format("{} was written by an earlier version of granflow (checkpoint format 1, before the history "
                       "held the side forces); run the case anew",
                       path.string());
  if (!in || h.magic != magic) return fmt::format("{} is not a granflow checkpoint", path.string());
  if (h.ranks != expected.ranks)
    return fmt::format("the checkpoint was written on {0} rank{1}; restart it on {0} rank{1}, not {2}", h.ranks,
                       h.ranks == 1 ? "" : "s", expected.ranks);
  if (h.nx != expected.nx || h.ny != expected.ny) return other_mesh(h.nx, h.ny, expected.nx, expected.ny);
  if (h.fields != expected.fields)
    return fmt::format("the checkpoint holds {} fields, this case needs {} (a different model or numerics)", h.fields,
                       expected.fields);
  for (Field* f : fields) {
    PetscInt n;
    VecGetLocalSize(f->local(), &n);
    std::int64_t size = -1;
    in.read(reinterpret_cast<char*>(&size), sizeof size);
    if (!in || size != n) return fmt::format("{}: a field's size does not match this rank's part of the mesh", path.string());
    PetscScalar* a;
    VecGetArray(f->local(), &a);
    in.read(reinterpret_cast<char*>(a), std::streamsize(sizeof(double) * n));
    VecRestoreArray(f->local(), &a);
    if (!in) return fmt::format("{} is truncated", path.string());
    f->gather_from_local();
  }
  scalars.assign(size_t(h.scalars), 0.0);
  in.read(reinterpret_cast<char*>(scalars.data()), std::streamsize(sizeof(double) * scalars.size()));
  if (!in) return fmt::format("{} is truncated", path.string());
  return {};
}

void write_run(const std::filesystem::path& path, const RunCheckpoint& r) {
  write_file_atomically(path, [&](std::ostream& out) {
    fmt::print(out, "time {:a}\nnext_dt {:a}\noutput_index {}\ndissipated_energy {:a}\ninitial_soil_volume {:a}\n", r.time,
               r.next_dt, r.output_index, r.dissipated_energy, r.initial_soil_volume);
    fmt::print(out, "series {}\n", r.series.size());
    for (const auto& [t, f] : r.series) fmt::print(out, "{:a} {}\n", t, f);
    fmt::print(out, "history {}\n", r.history.size());
    for (const auto& row : r.history) fmt::print(out, "{}\n", row);
    fmt::print(out, "domain {}\nsteps {}\nphysics {}\nfields {}\nboundaries {}\n", r.domain, r.steps, r.physics, r.fields,
               r.boundaries);
  });
}

// A number as write_run prints it (hexadecimal floating point); NaN if the text is not one, which
// the checks of the clock then refuse.
double hex_double(const std::string& s) {
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  return end == s.c_str() || *end != '\0' ? std::nan("") : x;
}

RunCheckpoint read_run(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw CheckpointError(fmt::format("cannot read {}", path.string()));
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
  }
  return r;
}

// Every rank throws if any rank failed, with the same message.
void agree(MPI_Comm comm, const std::string& mine) {
  if (auto text = first_failure(comm, mine); !text.empty()) throw CheckpointError(text);
}

}  // namespace

void write_checkpoint(MPI_Comm comm, const std::filesystem::path& dir, int nx, int ny, const RunCheckpoint& run,
                      std::span<Field* const> fields, std::span<const double> scalars) {
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const auto partial = dir / "checkpoint.partial", final_dir = dir / "checkpoint", old = dir / "checkpoint.old";
  if (rank == 0) {
    std::filesystem::remove_all(partial);
    std::filesystem::create_directories(partial);
  }
  MPI_Barrier(comm);
  const RankHeader h{magic, size, rank, nx, ny, std::int64_t(fields.size()), std::int64_t(scalars.size())};
  write_rank(rank_file(partial, rank), h, fields, scalars);
  if (rank == 0) write_run(partial / "run.txt", run);
  MPI_Barrier(comm);
  if (rank == 0) {
    // The last complete checkpoint is kept until the new one has its name: it is checkpoint/, or,
    // after a run killed between these renames, checkpoint.old/ alone, which must then not be
    // removed before the new one is in place.
    if (std::filesystem::exists(final_dir)) {
      std::filesystem::remove_all(old);
      std::filesystem::rename(final_dir, old);
    }
    std::filesystem::rename(partial, final_dir);
    std::filesystem::remove_all(old);
  }
  MPI_Barrier(comm);
}

RunCheckpoint read_checkpoint(MPI_Comm comm, const std::filesystem::path& dir, int nx, int ny,
                              const std::string& domain, const std::string& field_names,
                              std::span<Field* const> fields, std::vector<double>& scalars) {
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
  if (rank == 0) {
    try {
      run = read_run(from / "run.txt");
    } catch (const CheckpointError& e) {
      problem = fmt::format("the checkpoint is damaged: {}", e.what());
    } catch (const std::exception& e) {  // whatever else reading it throws must reach every rank too
      problem = fmt::format("the checkpoint is damaged: {}: {}", (from / "run.txt").string(), e.what());
    }
    if (problem.empty() && !run.domain.empty() && run.domain != domain) {
      // Another mesh blocks other cells of the same obstacles: name the mesh, the cause.
      const auto h = read_header(rank_file(from, 0));
      problem = h && (h->nx != nx || h->ny != ny)
                    ? other_mesh(h->nx, h->ny, nx, ny)
                    : fmt::format("the checkpoint is of the domain {}; the case's is {}", run.domain, domain);
    }
    // Other numerics may keep as many fields, of other meanings (cell forces where the look-ahead
    // keeps the last step's velocity): the names tell.
    if (problem.empty() && !run.fields.empty() && run.fields != field_names)
      problem = fmt::format("the checkpoint holds the fields of other numerics ({}); this case's are {}", run.fields,
                            field_names);
  }
  agree(comm, problem);
  const RankHeader expected{magic, size, rank, nx, ny, std::int64_t(fields.size()), 0};
  agree(comm, read_rank(rank_file(from, rank), expected, fields, scalars));
  double clock[6] = {run.time, run.next_dt, double(run.output_index), run.dissipated_energy, run.initial_soil_volume,
                     double(run.steps)};
  MPI_Bcast(clock, 6, MPI_DOUBLE, 0, comm);
  run.time = clock[0];
  run.next_dt = clock[1];
  run.output_index = int(clock[2]);
  run.dissipated_energy = clock[3];
  run.initial_soil_volume = clock[4];
  run.steps = long(clock[5]);
  return run;
}

}  // namespace granflow
