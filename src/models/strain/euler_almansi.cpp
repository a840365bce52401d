#include "models/strain/euler_almansi.hpp"

#include <cmath>

namespace granflow::strain {

bool almansi_strain(const DisplacementGradient& g, AlmansiStrain& e) {
  // F = I - grad u (Eq. 14)
  const double fxx = 1.0 - g.xx, fxy = -g.xy, fyx = -g.yx, fyy = 1.0 - g.yy;
  const double det = fxx * fyy - fxy * fyx;
  if (!(std::abs(det) > 1e-300) || !std::isfinite(det)) {
    e = {};
    return false;
  }
  // G = F^-1
  const double gxx = fyy / det, gxy = -fxy / det, gyx = -fyx / det, gyy = fxx / det;
  // e = (I - G G^T) / 2 (Eq. 13)
  e.xx = 0.5 * (1.0 - (gxx * gxx + gxy * gxy));
  e.yy = 0.5 * (1.0 - (gyx * gyx + gyy * gyy));
  e.xy = -0.5 * (gxx * gyx + gxy * gyy);
  return true;
}

double deviatoric_norm(const AlmansiStrain& e) {
  const double mean = (e.xx + e.yy) / 3.0;
  const double dxx = e.xx - mean, dyy = e.yy - mean, dzz = -mean;
  return std::sqrt(dxx * dxx + dyy * dyy + dzz * dzz + 2.0 * e.xy * e.xy);
}

}  // namespace granflow::strain
