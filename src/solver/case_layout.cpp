#include "solver/case_layout.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "io/collective_failure.hpp"
#include "mesh/gather.hpp"
#include "mesh/obstacles.hpp"
#include "models/interface/initial_shapes.hpp"
#include "solver/boundary.hpp"

namespace granflow {

// What laying the case on the mesh finds is of the case: named with its file, as reading it is.
CaseError case_error(const CaseConfig& config, const std::string& text) {
  return CaseError(config.source.empty() ? text : fmt::format("{}: {}", config.source.string(), text));
}

CaseError no_initial_soil(const CaseConfig& config, const Grid& g, bool obstacles) {
  if (obstacles)
    return case_error(config, fmt::format("initial.soil: the shapes place no soil in any open cell on this {} mesh "
                                          "(what they cover lies in the obstacles' blocked cells, or a shape is far "
                                          "smaller than a cell)", cell_counts(g.spec())));
  return case_error(config, fmt::format("initial.soil: the shapes cover no part of any cell's samples on this {} "
                                        "mesh (a shape far smaller than a cell)", cell_counts(g.spec())));
}

// Each soil material holds some soil once the shapes are laid out: one whose shapes all lie under
// shapes listed after it (the last listed holds a point), in blocked cells, or between the sample
// points that give each cell its shares (a seam thinner than a sixteenth of a cell), would be a
// material of no effect.
void check_materials_hold_soil(const CaseConfig& config, const std::vector<double>& volumes) {
  for (size_t k = 1; k < volumes.size(); ++k)
    if (!(volumes[k] > 0.0)) {
      const std::string& name = config.soil->materials[k - 1].name;
      throw case_error(config, fmt::format("soil.materials[{}]: '{}' holds no soil once the shapes are laid out: its "
                                           "shapes lie under shapes listed after them (where shapes overlap, the last "
                                           "listed holds the point){}, or are thinner than a sixteenth of a cell, "
                                           "between the 16 x 16 points that give each cell its shares (thicken them "
                                           "or refine the mesh)", k - 1, name,
                                           config.obstacles.empty() ? "" : ", in the obstacles' blocked cells"));
    }
}

namespace {
// The checks the whole mask needs, on rank 0: no obstacle one cell thick (the values mirrored behind
// a wall cannot serve both its sides, mesh/obstacles.hpp), and no open cells that the obstacles close
// off from every open side (their pressure would have no level); a closed domain's open cells are one
// region, whose level the coupled solve holds (coupled_step.cpp). Returns the problem, or "", and a
// hash of the blocked cells into `hash`.
std::string check_blocked_cells(const Grid& g, const CaseConfig& config, const std::vector<double>& m,
                                std::uint64_t& hash) {
  const int nx = g.nx(), ny = g.ny();
  auto blocked = [&](int i, int j) { return m[size_t(j) * nx + i] > 0.5; };
  auto wrap = [&](int i) { return g.periodic_x() ? (i + nx) % nx : i; };  // beyond a periodic side: the other end
  auto open = [&](int i, int j) {
    i = wrap(i);
    return i >= 0 && i < nx && j >= 0 && j < ny && !blocked(i, j);
  };
  hash = 1469598103934665603ULL;  // FNV-1a over the blocked cells' indices
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (blocked(i, j)) {
        for (long v = long(j) * nx + i, k = 0; k < 8; ++k, v >>= 8) hash = (hash ^ std::uint64_t(v & 0xff)) * 1099511628211ULL;
        if ((open(i - 1, j) && open(i + 1, j)) || (open(i, j - 1) && open(i, j + 1)))
          return fmt::format("obstacle: the cell at x = {:.4g} m, y = {:.4g} m is a wall one cell thick, with the flow on "
                             "both sides; make the obstacles at least two cells thick on this {} x {} mesh",
                             g.xc(i), g.yc(j), nx, ny);
      }
  // Regions of open cells (4-connected), and whether each reaches an open side of the domain.
  std::vector<int> region(size_t(nx) * ny, -1);
  std::vector<bool> reaches_open_side;
  std::vector<std::array<int, 2>> first_cell;
  auto open_side = [&](int i, int j) {
    auto is_open = [&](Side s) { return boundary(config.flow.boundaries, s).kind == BoundaryKind::atmosphere; };
    return (i == 0 && is_open(Side::west)) || (i == nx - 1 && is_open(Side::east)) ||
           (j == 0 && is_open(Side::south)) || (j == ny - 1 && is_open(Side::north));
  };
  std::vector<std::array<int, 2>> stack;
  for (int j = ny - 1; j >= 0; --j)
    for (int i = 0; i < nx; ++i) {
      if (!open(i, j) || region[size_t(j) * nx + i] >= 0) continue;
      const int r = int(reaches_open_side.size());
      reaches_open_side.push_back(false);
      first_cell.push_back({i, j});
      stack.push_back({i, j});
      region[size_t(j) * nx + i] = r;
      while (!stack.empty()) {
        const auto [ci, cj] = stack.back();
        stack.pop_back();
        if (open_side(ci, cj)) reaches_open_side[r] = true;
        for (const auto& [di, dj] : {std::array<int, 2>{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
          if (const int ni = wrap(ci + di); open(ni, cj + dj) && region[size_t(cj + dj) * nx + ni] < 0) {
            region[size_t(cj + dj) * nx + ni] = r;
            stack.push_back({ni, cj + dj});
          }
      }
    }
  for (size_t r = 0; r < reaches_open_side.size(); ++r)
    if (!reaches_open_side[r] && reaches_open_side.size() > 1)
      return fmt::format("obstacle: the open cells around x = {:.4g} m, y = {:.4g} m are closed off by the obstacles "
                         "from {} (their pressure would have no level); block them too, or open them to the rest",
                         g.xc(first_cell[r][0]), g.yc(first_cell[r][1]),
                         std::count(reaches_open_side.begin(), reaches_open_side.end(), true) > 0
                             ? "every open side" : "the rest of the domain");
  return {};
}
}  // namespace


// Marks the cells of the case's obstacles into mask (mesh/obstacles.hpp). A cell is blocked whole,
// by its centre: an obstacle that holds no cell's centre on this mesh would be silently missing,
// and one that blocks every cell leaves no flow. Collective; every rank throws alike.
ObstacleLayout lay_out_obstacles(const Grid& g, const CaseConfig& config, Field& mask) {
  std::vector<long> centres(config.obstacles.size(), 0);
  const interface::ShapeUnion obstacles(config.obstacles);
  const auto& b = g.owned();
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i)
      for (size_t k = 0; k < centres.size(); ++k) centres[k] += obstacles.shape_contains(k, g.xc(i), g.yc(j));
  MPI_Allreduce(MPI_IN_PLACE, centres.data(), int(centres.size()), MPI_LONG, MPI_SUM, g.comm());
  for (size_t k = 0; k < centres.size(); ++k)
    if (centres[k] == 0)
      throw case_error(config, fmt::format("obstacle[{}]: the shape holds no cell centre on this {} x {} mesh (cells are "
                                  "blocked whole, by their centres)", k, g.nx(), g.ny()));
  ObstacleLayout layout;
  layout.blocked_cells = mark_blocked_cells(g, obstacles, mask);
  if (layout.blocked_cells == g.cell_count()) throw case_error(config, "obstacle: the obstacles block every cell of the domain");
  if (config.soil && config.soil->yield_pressure == YieldPressure::lithostatic_floor)
    throw case_error(config, "obstacle: soil.yield_pressure = \"lithostatic_floor\" takes the soil above each cell up to the "
                    "top, through any obstacle; use \"face\" or \"cell\" with obstacles");
  layout.mask_on_root = gather_to_root(g, mask);
  std::string problem;
  int rank;
  MPI_Comm_rank(g.comm(), &rank);
  if (rank == 0) problem = check_blocked_cells(g, config, layout.mask_on_root, layout.hash);
  if (auto text = first_failure(g.comm(), problem); !text.empty()) throw case_error(config, text);
  MPI_Bcast(&layout.hash, 1, MPI_UINT64_T, 0, g.comm());
  return layout;
}

PlacedSoil initial_soil_placed(const Grid& g, const CaseConfig& config, const Field* mask) {
  if (g.dimension() == 3) {  // as SoilPhase lays it (soil_phase_3d.cpp); no obstacles there
    const interface::ShapeUnion3 soil(config.soil->initial_solids(g.spec().lower[2], g.spec().upper[2]));
    const auto& b = g.owned();
    double volume = 0.0;
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          const interface::Point3 lower{g.xc(i) - 0.5 * g.dx(i), g.yc(j) - 0.5 * g.dy(j), g.zc(k) - 0.5 * g.dz(k)};
          volume += soil.fraction(lower, {lower[0] + g.dx(i), lower[1] + g.dy(j), lower[2] + g.dz(k)}) * g.volume(i, j, k);
        }
    MPI_Allreduce(MPI_IN_PLACE, &volume, 1, MPI_DOUBLE, MPI_SUM, g.comm());
    return {volume, 0.0};
  }
  const BlockedView blocked(g, mask);
  const interface::ShapeUnion initial_soil(config.soil->initial_soil);
  const auto& b = g.owned();
  double volumes[2] = {0.0, 0.0};
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      const double x0 = g.xc(i) - 0.5 * g.dx(i), y0 = g.yc(j) - 0.5 * g.dy(j);
      volumes[is_blocked(blocked.data(), i, j) ? 1 : 0] +=
          initial_soil.fraction(x0, x0 + g.dx(i), y0, y0 + g.dy(j), g.axisymmetric()) * g.volume(i, j);
    }
  MPI_Allreduce(MPI_IN_PLACE, volumes, 2, MPI_DOUBLE, MPI_SUM, g.comm());
  return {volumes[0], volumes[1]};
}

}  // namespace granflow
