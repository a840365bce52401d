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

bool almansi_strain(const DisplacementGradient3& grad_u, AlmansiStrain3& e) {
  // F = I - grad u (Eq. 14), G = F^-1 by its adjugate.
  double f[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f[i][j] = (i == j ? 1.0 : 0.0) - grad_u.g[i][j];
  double adj[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      adj[i][j] = f[r0][c0] * f[r1][c1] - f[r0][c1] * f[r1][c0];  // cofactor of f[j][i]
    }
  const double det = f[0][0] * adj[0][0] + f[0][1] * adj[1][0] + f[0][2] * adj[2][0];
  if (!(std::abs(det) > 1e-300) || !std::isfinite(det)) {
    e = {};
    return false;
  }
  double g[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) g[i][j] = adj[i][j] / det;
  // e = (I - G G^T) / 2 (Eq. 13)
  auto ggt = [&](int i, int j) { return g[i][0] * g[j][0] + g[i][1] * g[j][1] + g[i][2] * g[j][2]; };
  e.xx = 0.5 * (1.0 - ggt(0, 0));
  e.yy = 0.5 * (1.0 - ggt(1, 1));
  e.zz = 0.5 * (1.0 - ggt(2, 2));
  e.xy = -0.5 * ggt(0, 1);
  e.xz = -0.5 * ggt(0, 2);
  e.yz = -0.5 * ggt(1, 2);
  return true;
}

double deviatoric_norm(const AlmansiStrain3& e) {
  const double mean = (e.xx + e.yy + e.zz) / 3.0;
  const double dxx = e.xx - mean, dyy = e.yy - mean, dzz = e.zz - mean;
  return std::sqrt(dxx * dxx + dyy * dyy + dzz * dzz + 2.0 * (e.xy * e.xy + e.xz * e.xz + e.yz * e.yz));
}

}  // namespace granflow::strain
