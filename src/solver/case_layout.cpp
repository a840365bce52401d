#include "solver/case_layout.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "io/collective_failure.hpp"
#include "mesh/gather.hpp"
#include "mesh/obstacles.hpp"
#include "mesh/thin_ridges.hpp"
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
  auto inlet_carries = [&](size_t k) {  // a material an inlet brings in may start with none
    return std::any_of(config.flow.boundaries.begin(), config.flow.boundaries.end(), [&](const BoundaryCondition& bc) {
      return carries_soil(bc) && size_t(bc.inflow_material) == k;
    });
  };
  for (size_t k = 1; k < volumes.size(); ++k)
    if (!(volumes[k] > 0.0) && !inlet_carries(k)) {
      const std::string& name = config.soil->materials[k - 1].name;
      throw case_error(config, fmt::format("soil.materials[{}]: '{}' holds no soil once the shapes are laid out: its "
                                           "shapes lie under shapes listed after them (where shapes overlap, the last "
                                           "listed holds the point){}, or are thinner than a sixteenth of a cell, "
                                           "between the {} points that give each cell its shares (thicken them "
                                           "or refine the mesh)", k - 1, name,
                                           config.has_obstacles() ? ", in the obstacles' blocked cells" : "",
                                           config.mesh.dimension() == 3 ? "16 x 16 x 16" : "16 x 16"));
    }
}

namespace {
// The checks the whole mask needs, on rank 0: no obstacle one cell thick (the values mirrored behind
// a wall cannot serve both its sides, mesh/obstacles.hpp), and no open cells that the obstacles close
// off from every open side (their pressure would have no level); a closed domain's open cells are one
// region, whose level the coupled solve holds (coupled_step.cpp). Returns the problem, or "", and a
// hash of the blocked cells into `hash`. Planar meshes are one layer along z.
std::string check_blocked_cells(const Grid& g, const CaseConfig& config, const std::vector<double>& m,
                                std::uint64_t& hash) {
  const int nx = g.nx(), ny = g.ny(), nz = g.nz();
  const bool layers = g.dimension() == 3;
  auto index = [&](int i, int j, int k) { return (size_t(k) * ny + j) * nx + i; };
  auto blocked = [&](int i, int j, int k) { return m[index(i, j, k)] > 0.5; };
  auto wrap = [&](int i) { return g.periodic_x() ? (i + nx) % nx : i; };  // beyond a periodic side: the other end
  auto open = [&](int i, int j, int k) {
    i = wrap(i);
    return i >= 0 && i < nx && j >= 0 && j < ny && k >= 0 && k < nz && !blocked(i, j, k);
  };
  auto where = [&](int i, int j, int k) {
    return layers ? fmt::format("x = {:.4g} m, y = {:.4g} m, z = {:.4g} m", g.xc(i), g.yc(j), g.zc(k))
                  : fmt::format("x = {:.4g} m, y = {:.4g} m", g.xc(i), g.yc(j));
  };
  using Cell = std::array<int, 3>;
  constexpr Cell steps[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const int step_count = layers ? 6 : 4;
  hash = 1469598103934665603ULL;  // FNV-1a over the blocked cells' indices
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (blocked(i, j, k)) {
          for (long v = long(index(i, j, k)), b = 0; b < 8; ++b, v >>= 8) hash = (hash ^ std::uint64_t(v & 0xff)) * 1099511628211ULL;
          for (Side s : sides_of_dimension(g.dimension())) {  // an inlet's flow would enter the obstacle
            const int at[3] = {i, j, k}, n[3] = {nx, ny, nz};
            const int axis = normal_axis(s);
            const bool on_side = at[axis] == (is_low_side(s) ? 0 : n[axis] - 1);
            if (on_side && lets_in(boundary(config.flow.boundaries, s), g, s, i, j, k))
              return fmt::format("obstacle: the cell at {} is blocked against the inlet on the {} side, whose flow "
                                 "would enter it; keep the obstacles off the inlet's side",
                                 where(i, j, k), side_name(s));
          }
          for (int s = 0; s < step_count; s += 2) {
            const Cell& d = steps[s];
            if (open(i - d[0], j - d[1], k - d[2]) && open(i + d[0], j + d[1], k + d[2]))
              return fmt::format("obstacle: the cell at {} is a wall one cell thick, with the flow on both sides; make "
                                 "the obstacles at least two cells thick on this {} mesh", where(i, j, k),
                                 cell_counts(g.spec()));
          }
        }
  // Regions of open cells (face-connected), and whether each reaches an open side of the domain.
  std::vector<int> region(size_t(nx) * ny * nz, -1);
  std::vector<bool> reaches_open_side;
  std::vector<Cell> first_cell;
  auto open_side = [&](int i, int j, int k) {
    auto is_open = [&](Side s) { return boundary(config.flow.boundaries, s).kind == BoundaryKind::atmosphere; };
    return (i == 0 && is_open(Side::west)) || (i == nx - 1 && is_open(Side::east)) ||
           (j == 0 && is_open(Side::south)) || (j == ny - 1 && is_open(Side::north)) ||
           (layers && ((k == 0 && is_open(Side::front)) || (k == nz - 1 && is_open(Side::back))));
  };
  std::vector<Cell> stack;
  for (int k = 0; k < nz; ++k)
    for (int j = ny - 1; j >= 0; --j)
      for (int i = 0; i < nx; ++i) {
        if (!open(i, j, k) || region[index(i, j, k)] >= 0) continue;
        const int r = int(reaches_open_side.size());
        reaches_open_side.push_back(false);
        first_cell.push_back({i, j, k});
        stack.push_back({i, j, k});
        region[index(i, j, k)] = r;
        while (!stack.empty()) {
          const auto [ci, cj, ck] = stack.back();
          stack.pop_back();
          if (open_side(ci, cj, ck)) reaches_open_side[r] = true;
          for (int s = 0; s < step_count; ++s) {
            const int ni = wrap(ci + steps[s][0]), nj = cj + steps[s][1], nk = ck + steps[s][2];
            if (open(ni, nj, nk) && region[index(ni, nj, nk)] < 0) {
              region[index(ni, nj, nk)] = r;
              stack.push_back({ni, nj, nk});
            }
          }
        }
      }
  for (size_t r = 0; r < reaches_open_side.size(); ++r)
    if (!reaches_open_side[r] && reaches_open_side.size() > 1)
      return fmt::format("obstacle: the open cells around {} are closed off by the obstacles from {} (their pressure "
                         "would have no level); block them too, or open them to the rest",
                         where(first_cell[r][0], first_cell[r][1], first_cell[r][2]),
                         std::count(reaches_open_side.begin(), reaches_open_side.end(), true) > 0
                             ? "every open side" : "the rest of the domain");
  return {};
}

// How many owned cells' centres each obstacle holds.
std::vector<long> centres_held(const Grid& g, const CaseConfig& config) {
  const auto& b = g.owned();
  if (g.dimension() == 3) {
    std::vector<long> centres(config.obstacle_solids.size(), 0);
    for (size_t n = 0; n < centres.size(); ++n) {
      const interface::ShapeUnion3 solid({config.obstacle_solids[n]});
      for (int k = b.zs; k < b.ze(); ++k)
        for (int j = b.ys; j < b.ye(); ++j)
          for (int i = b.xs; i < b.xe(); ++i) centres[n] += solid.contains(g.xc(i), g.yc(j), g.zc(k));
    }
    return centres;
  }
  std::vector<long> centres(config.obstacles.size(), 0);
  const interface::ShapeUnion obstacles(config.obstacles);
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i)
      for (size_t k = 0; k < centres.size(); ++k) centres[k] += obstacles.shape_contains(k, g.xc(i), g.yc(j));
  return centres;
}

// The ridges one cell wide of the obstacles that lower theirs (height maps, mesh/thin_ridges.hpp), opened
// in the mask, its copy on rank 0 and the layout's counts. A cell is opened only where no obstacle that
// keeps its ridges holds its centre. Collective.
void lower_thin_ridges(const Grid& g, const CaseConfig& config, const interface::ShapeUnion3& solids, Field& mask,
                       ObstacleLayout& layout) {
  const auto& lowers = config.obstacle_lowers_thin_ridges;
  if (g.dimension() != 3 || std::find(lowers.begin(), lowers.end(), true) == lowers.end()) return;
  int rank;
  MPI_Comm_rank(g.comm(), &rank);
  std::vector<long> opened;
  const size_t count_of_solids = config.obstacle_solids.size();
  auto lowers_its = [&](size_t s) { return s < lowers.size() && lowers[s]; };
  layout.ridge_cells_opened.assign(count_of_solids, 0);
  if (rank == 0) {
    const long nx = g.nx(), ny = g.ny();
    auto centre_of = [&](long n) { return cell_of_index(n, nx, ny); };
    opened = open_thin_ridges(g.nx(), g.ny(), g.nz(), g.periodic_x(), layout.mask_on_root, [&](long n) {
      const auto [i, j, k] = centre_of(n);
      for (size_t s = 0; s < count_of_solids; ++s)
        if (!lowers_its(s) && solids.shape_contains(s, g.xc(i), g.yc(j), g.zc(k))) return false;
      return true;  // blocked, so held by an obstacle, and by none that keeps its ridges
    });
    for (const long n : opened) {
      const auto [i, j, k] = centre_of(n);
      size_t holder = 0;
      for (size_t s = 0; s < count_of_solids; ++s)
        if (solids.shape_contains(s, g.xc(i), g.yc(j), g.zc(k))) holder = s;  // the last listed, as the mask's index
      ++layout.ridge_cells_opened[holder];
      layout.ridge_volume_opened += g.volume(i, j, k);
    }
  }
  long count = long(opened.size());
  MPI_Bcast(&count, 1, MPI_LONG, 0, g.comm());
  if (count == 0) return;
  opened.resize(size_t(count));
  MPI_Bcast(opened.data(), int(count), MPI_LONG, 0, g.comm());
  MPI_Bcast(layout.ridge_cells_opened.data(), int(count_of_solids), MPI_LONG, 0, g.comm());
  MPI_Bcast(&layout.ridge_volume_opened, 1, MPI_DOUBLE, 0, g.comm());
  layout.blocked_cells = mark_blocked_cells(g, solids, mask, opened);
}
}  // namespace


// Marks the cells of the case's obstacles into mask (mesh/obstacles.hpp). A cell is blocked whole,
// by its centre: an obstacle that holds no cell's centre on this mesh would be silently missing,
// and one that blocks every cell leaves no flow. Collective; every rank throws alike.
ObstacleLayout lay_out_obstacles(const Grid& g, const CaseConfig& config, Field& mask) {
  std::vector<long> centres = centres_held(g, config);
  MPI_Allreduce(MPI_IN_PLACE, centres.data(), int(centres.size()), MPI_LONG, MPI_SUM, g.comm());
  for (size_t k = 0; k < centres.size(); ++k)
    if (centres[k] == 0)
      throw case_error(config, fmt::format("obstacle[{}]: the shape holds no cell centre on this {} mesh (cells are "
                                  "blocked whole, by their centres)", k, cell_counts(g.spec())));
  ObstacleLayout layout;
  const interface::ShapeUnion3 solids(config.obstacle_solids);
  layout.blocked_cells = g.dimension() == 3 ? mark_blocked_cells(g, solids, mask)
                                            : mark_blocked_cells(g, interface::ShapeUnion(config.obstacles), mask);
  if (config.soil && config.soil->yield_pressure == YieldPressure::lithostatic_floor)
    throw case_error(config, "obstacle: soil.yield_pressure = \"lithostatic_floor\" takes the soil above each cell up to the "
                    "top, through any obstacle; use \"face\" or \"cell\" with obstacles");
  layout.mask_on_root = gather_to_root(g, mask);
  int rank;
  MPI_Comm_rank(g.comm(), &rank);
  lower_thin_ridges(g, config, solids, mask, layout);
  if (layout.blocked_cells == g.cell_count()) throw case_error(config, "obstacle: the obstacles block every cell of the domain");
  std::string problem;
  if (rank == 0) problem = check_blocked_cells(g, config, layout.mask_on_root, layout.hash);
  if (auto text = first_failure(g.comm(), problem); !text.empty()) throw case_error(config, text);
  MPI_Bcast(&layout.hash, 1, MPI_UINT64_T, 0, g.comm());
  return layout;
}

std::string ridges_lowered(const ObstacleLayout& layout) {
  std::string which;
  long total = 0;
  for (size_t s = 0; s < layout.ridge_cells_opened.size(); ++s)
    if (const long n = layout.ridge_cells_opened[s]; n > 0) {
      which += fmt::format("obstacle[{}]: {}, ", s, n);
      total += n;
    }
  if (total == 0) return {};
  return fmt::format("{} cell{} of ridges one cell wide lowered to the mesh ({}{:.6g} m^3)", total,
                     total == 1 ? "" : "s", which, layout.ridge_volume_opened);
}

PlacedSoil initial_soil_placed(const Grid& g, const CaseConfig& config, const Field* mask) {
  const BlockedView blocked(g, mask);
  double volumes[2] = {0.0, 0.0};
  if (g.dimension() == 3) {  // as SoilPhase lays it (soil_phase_3d.cpp)
    const interface::ShapeUnion3 soil(config.soil->initial_solids(g.spec().lower[2], g.spec().upper[2]));
    const auto& b = g.owned();
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          const interface::Point3 lower{g.xc(i) - 0.5 * g.dx(i), g.yc(j) - 0.5 * g.dy(j), g.zc(k) - 0.5 * g.dz(k)};
          volumes[is_blocked(blocked.data(), i, j, k) ? 1 : 0] +=
              soil.fraction(lower, {lower[0] + g.dx(i), lower[1] + g.dy(j), lower[2] + g.dz(k)}) * g.volume(i, j, k);
        }
    MPI_Allreduce(MPI_IN_PLACE, volumes, 2, MPI_DOUBLE, MPI_SUM, g.comm());
    return {volumes[0], volumes[1]};
  }
  const interface::ShapeUnion initial_soil(config.soil->initial_soil);
  const auto& b = g.owned();
  for (int j = b.ys; j < b.ye(); ++j)
    for (int i = b.xs; i < b.xe(); ++i) {
      const double x0 = g.xc(i) - 0.5 * g.dx(i), y0 = g.yc(j) - 0.5 * g.dy(j);
      volumes[is_blocked(blocked.data(), i, j, 0) ? 1 : 0] +=
          initial_soil.fraction(x0, x0 + g.dx(i), y0, y0 + g.dy(j), g.axisymmetric()) * g.volume(i, j);
    }
  MPI_Allreduce(MPI_IN_PLACE, volumes, 2, MPI_DOUBLE, MPI_SUM, g.comm());
  return {volumes[0], volumes[1]};
}

}  // namespace granflow
