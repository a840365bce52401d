#include "models/interface/wetted_fraction.hpp"

#include <algorithm>

#include "models/interface/plic_geometry.hpp"

namespace granflow::interface {

double wetted_side_fraction(const double* const* c, const double* dx, const double* dy, int i, int j,
                            int axis, int sign) {
  const double cc = c[j][i];
  if (cc <= 0.0) return 0.0;
  if (cc >= 1.0) return 1.0;
  const Block3x3 b = gather_block(c, dx, dy, i, j);
  double lo = b.c[0][0], hi = b.c[0][0];
  for (const auto& row : b.c)
    for (const double v : row) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (hi - lo < 1e-8) return cc;  // the same flat-block rule as the advection's
  const Normal2 n = myc_normal(b);
  if (n.nx == 0.0 && n.ny == 0.0) return cc;
  return side_fraction(n, line_alpha(cc, n), axis, sign);
}

}  // namespace granflow::interface
