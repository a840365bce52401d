#include "solver/velocity_ghosts.hpp"

namespace granflow {

namespace {
// The ghost of velocity component `component` at a side normal to `normal`, whose mirror image inside
// holds `inner` and whose first cell holds `first`.
double ghost(const BoundaryCondition& bc, int component, int normal, double inner, double first) {
  switch (bc.kind) {
    case BoundaryKind::wall: return 2.0 * bc.wall_velocity[component] - inner;
    case BoundaryKind::slip: return component == normal ? -inner : inner;
    case BoundaryKind::atmosphere: return first;
    case BoundaryKind::periodic: break;  // no ghost of its own: the exchange filled it
  }
  return inner;
}
}  // namespace

void fill_velocity_side_ghosts(const Grid& grid, const BoundarySet& boundaries, std::span<double*** const> components) {
  const auto& b = grid.owned();
  const int n[3] = {grid.nx(), grid.ny(), grid.nz()}, gw = Grid::ghost_width;
  const int lo[3] = {b.xs - gw, b.ys - gw, b.zs - gw}, hi[3] = {b.xe() + gw, b.ye() + gw, b.ze() + gw};
  for (std::size_t c = 0; c < components.size(); ++c) {
    double*** f = components[c];
    for (int axis = 0; axis < 3 && axis < grid.dimension(); ++axis) {
      constexpr Side low_sides[3] = {Side::west, Side::south, Side::front}, high_sides[3] = {Side::east, Side::north, Side::back};
      const Side low_side = low_sides[axis], high_side = high_sides[axis];
      const bool low = grid.owns_boundary(low_side), high = grid.owns_boundary(high_side);
      if (!low && !high) continue;
      const BoundaryCondition &low_bc = boundary(boundaries, low_side), &high_bc = boundary(boundaries, high_side);
      // The transverse axes, the outer one first; on a planar mesh the only layer.
      const int t1 = axis == 0 ? 1 : 0, t2 = axis == 2 ? 1 : 2;
      const int t2_lo = grid.dimension() == 3 ? lo[t2] : 0, t2_hi = grid.dimension() == 3 ? hi[t2] : 1;
      int p[3];
      for (int m = 1; m <= gw; ++m)
        for (p[t2] = t2_lo; p[t2] < t2_hi; ++p[t2])
          for (p[t1] = lo[t1]; p[t1] < hi[t1]; ++p[t1]) {
            auto cell = [&](int along) -> double& {
              int q[3] = {p[0], p[1], p[2]};
              q[axis] = along;
              return f[q[2]][q[1]][q[0]];
            };
            const int c_int = int(c);
            if (low) cell(-m) = ghost(low_bc, c_int, axis, cell(m - 1), cell(0));
            if (high) cell(n[axis] - 1 + m) = ghost(high_bc, c_int, axis, cell(n[axis] - m), cell(n[axis] - 1));
          }
    }
  }
}

}  // namespace granflow
