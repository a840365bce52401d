#include "solver/velocity_ghosts.hpp"

#include "mesh/side_ghosts.hpp"

namespace granflow {

namespace {
// The ghost of velocity component `component` at a side normal to `normal`, whose mirror image inside
// holds `inner` and whose first cell holds `first`; `wall` the velocity the side holds there.
double ghost(const BoundaryCondition& bc, const std::array<double, 3>& wall, int component, int normal, double inner,
             double first) {
  switch (bc.kind) {
    case BoundaryKind::wall:
    case BoundaryKind::inlet: return 2.0 * wall[component] - inner;
    case BoundaryKind::slip: return component == normal ? -inner : inner;
    case BoundaryKind::atmosphere: return first;
    case BoundaryKind::periodic: break;  // no ghost of its own: the exchange filled it
  }
  return inner;
}
}  // namespace

void fill_velocity_side_ghosts(const Grid& grid, const BoundarySet& boundaries, std::span<double*** const> components) {
  for (std::size_t c = 0; c < components.size(); ++c)
    fill_side_ghosts(grid, components[c], [&](Side side, double inner, double first, const int* at) {
      const auto& bc = boundary(boundaries, side);
      return ghost(bc, held_velocity(bc, grid, side, at[0], at[1], at[2]), int(c), normal_axis(side), inner, first);
    });
}

}  // namespace granflow
