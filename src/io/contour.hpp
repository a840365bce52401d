#pragma once
// Iso-lines of a cell-centred field by marching squares over the dual grid of cell centres.
#include <functional>
#include <vector>

#include "mesh/grid.hpp"

namespace granflow {

struct Segment {
  double x0, y0, x1, y1;
};

// Segments of the line value == level of a gathered field (natural order). `keep` may reject a
// square of four cells (given its lower-left cell i, j), e.g. to keep a line inside the soil.
std::vector<Segment> iso_line(const Grid& grid, const std::vector<double>& values, double level,
                              const std::function<bool(int, int)>& keep = {});

}  // namespace granflow
