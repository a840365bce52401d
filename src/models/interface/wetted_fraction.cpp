#include "models/interface/wetted_fraction.hpp"

#include "models/interface/plic_geometry.hpp"

namespace granflow::interface {

double wetted_side_fraction(const double* const* c, const double* dx, const double* dy, int i, int j,
                            int axis, int sign, const double* radius_centre) {
  const double cc = c[j][i];
  if (cc <= 0.0) return 0.0;
  if (cc >= 1.0) return 1.0;
  const double rho = radius_centre != nullptr ? radius_centre[i] / dx[i] : 0.0;
  const bool weighted = rho >= 0.5;
  const CellLine line = cell_line(gather_block(c, dx, dy, i, j), weighted ? rho : 0.0);
  if (!line.found) return cc;
  return weighted ? weighted_side_fraction(line.n, line.alpha, axis, sign, rho) : side_fraction(line.n, line.alpha, axis, sign);
}

}  // namespace granflow::interface
