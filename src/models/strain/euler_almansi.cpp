#include "models/strain/euler_almansi.hpp"

#include <cmath>

namespace granflow::strain {

bool almansi_strain(const DisplacementGradient& g, AlmansiStrain& e) {
  // F = I - grad u (Eq. 14); block-diagonal: the in-plane 2x2 and the hoop entry.
  const double fxx = 1.0 - g.xx, fxy = -g.xy, fyx = -g.yx, fyy = 1.0 - g.yy;
  const double f_hoop = 1.0 - g.hoop;
  const double det = fxx * fyy - fxy * fyx;
  if (!(std::abs(det) > 1e-300) || !std::isfinite(det) || !(std::abs(f_hoop) > 1e-300)) {
    e = {};
    return false;
  }
  // G = F^-1
  const double gxx = fyy / det, gxy = -fxy / det, gyx = -fyx / det, gyy = fxx / det;
  const double g_hoop = 1.0 / f_hoop;
  // e = (I - G G^T) / 2 (Eq. 13)
  e.xx = 0.5 * (1.0 - (gxx * gxx + gxy * gxy));
  e.yy = 0.5 * (1.0 - (gyx * gyx + gyy * gyy));
  e.xy = -0.5 * (gxx * gyx + gxy * gyy);
  e.hoop = 0.5 * (1.0 - g_hoop * g_hoop);
  return true;
}

double deviatoric_norm(const AlmansiStrain& e) {
  const double mean = (e.xx + e.yy + e.hoop) / 3.0;
  const double dxx = e.xx - mean, dyy = e.yy - mean, dzz = e.hoop - mean;
  return std::sqrt(dxx * dxx + dyy * dyy + dzz * dzz + 2.0 * e.xy * e.xy);
}

}  // namespace granflow::strain
