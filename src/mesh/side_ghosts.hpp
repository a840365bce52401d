#pragma once
// The passes that fill a field's ghost layers beyond the domain's sides, whatever rule a side's ghosts
// follow: along x, then y, then z (x and y on a planar mesh, whose one layer has no z ghosts), each pass
// over the ghost rows of those before, so that an edge's or a corner's ghost ends as the later side's
// rule applied to the earlier side's ghosts. Only the sides this rank holds (Grid::owns_boundary) are
// filled: a periodic side's ghosts are the exchange's.
#include <type_traits>

#include "mesh/grid.hpp"

namespace granflow {

// rule(side, inner, first): a ghost m layers beyond `side` (m = 1 .. ghost width), whose mirror image
// inside (m - 1 layers in) holds `inner` and whose first cell holds `first`; or rule(side, inner,
// first, where), `where` the ghost's indices {i, j, k} (a rule that varies along the side). a: the
// local array.
template <class Rule>
void fill_side_ghosts(const Grid& grid, double*** a, Rule rule) {
  const int n[3] = {grid.nx(), grid.ny(), grid.nz()}, gw = Grid::ghost_width;
  const bool layers = grid.dimension() == 3;
  const CellBox e = grid.with_ghosts();
  const int lo[3] = {e.xs, e.ys, e.zs}, hi[3] = {e.xe(), e.ye(), e.ze()};
  constexpr Side low_sides[3] = {Side::west, Side::south, Side::front};
  constexpr Side high_sides[3] = {Side::east, Side::north, Side::back};
  for (int axis = 0; axis < (layers ? 3 : 2); ++axis) {
    const Side low_side = low_sides[axis], high_side = high_sides[axis];
    const bool low = grid.owns_boundary(low_side), high = grid.owns_boundary(high_side);
    if (!low && !high) continue;
    // The axes across the pass, the outer one first.
    const int t1 = axis == 0 ? 1 : 0, t2 = axis == 2 ? 1 : 2;
    int p[3];
    for (int m = 1; m <= gw; ++m)
      for (p[t2] = lo[t2]; p[t2] < hi[t2]; ++p[t2])
        for (p[t1] = lo[t1]; p[t1] < hi[t1]; ++p[t1]) {
          auto cell = [&](int along) -> double& {
            int q[3] = {p[0], p[1], p[2]};
            q[axis] = along;
            return a[q[2]][q[1]][q[0]];
          };
          auto apply = [&](Side side, int along, double inner, double first) {
            if constexpr (std::is_invocable_v<Rule, Side, double, double, const int*>) {
              int q[3] = {p[0], p[1], p[2]};
              q[axis] = along;
              return rule(side, inner, first, static_cast<const int*>(q));
            } else {
              return rule(side, inner, first);
            }
          };
          if (low) cell(-m) = apply(low_side, -m, cell(m - 1), cell(0));
          if (high) cell(n[axis] - 1 + m) = apply(high_side, n[axis] - 1 + m, cell(n[axis] - m), cell(n[axis] - 1));
        }
  }
}

}  // namespace granflow
