#include "models/interface/wetted_fraction.hpp"

#include "models/interface/plic_geometry.hpp"
#include "models/interface/plic_geometry_3d.hpp"

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

double wetted_side_fraction(const double* const* const* c, const double* dx, const double* dy, const double* dz,
                            int i, int j, int k, int axis, int sign) {
  const double cc = c[k][j][i];
  if (cc <= 0.0) return 0.0;
  if (cc >= 1.0) return 1.0;
  Block3x3x3 b;
  double lo = cc, hi = cc;
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q)
      for (int p = 0; p < 3; ++p) {
        const double v = c[k - 1 + r][j - 1 + q][i - 1 + p];
        b.c[r][q][p] = v;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  for (int d = 0; d < 3; ++d) {
    b.dx[d] = dx[i - 1 + d];
    b.dy[d] = dy[j - 1 + d];
    b.dz[d] = dz[k - 1 + d];
  }
  if (hi - lo < 1e-8) return cc;  // too flat to orient, as in 2D
  const Normal3 n = myc_normal(b);
  if (n.nx == 0.0 && n.ny == 0.0 && n.nz == 0.0) return cc;
  return face_fraction(n, plane_alpha(cc, n), axis, sign);
}

}  // namespace granflow::interface
