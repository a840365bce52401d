// Shared helpers for the rheology tests: random strain rates and rotations.
#pragma once

#include <array>
#include <cmath>
#include <random>

#include "models/rheology/tensor.hpp"

namespace granflow::rheology::testing {

using Matrix3 = std::array<std::array<double, 3>, 3>;

// Rotation matrix of a random unit quaternion.
inline Matrix3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  double q[4];
  double length = 0.0;
  for (double& c : q) {
    c = normal(rng);
    length += c * c;
  }
  length = std::sqrt(length);
  const double w = q[0] / length, x = q[1] / length, y = q[2] / length, z = q[3] / length;
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

// Q A Q^T.
inline SymmetricTensor rotate(const SymmetricTensor& a, const Matrix3& q) {
  const Matrix3 m{{{a.xx, a.xy, a.xz}, {a.xy, a.yy, a.yz}, {a.xz, a.yz, a.zz}}};
  Matrix3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) s += q[i][k] * m[k][l] * q[j][l];
      r[i][j] = s;
    }
  return {r[0][0], r[1][1], r[2][2], 0.5 * (r[0][1] + r[1][0]), 0.5 * (r[0][2] + r[2][0]),
          0.5 * (r[1][2] + r[2][1])};
}

// A random traceless, fully 3D strain rate with ||D|| spread over five decades.
inline StrainRate random_traceless_strain_rate(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> decade(-3.0, 2.0);
  SymmetricTensor d{unit(rng), unit(rng), unit(rng), unit(rng), unit(rng), unit(rng)};
  d = deviatoric(d);
  return std::pow(10.0, decade(rng)) * d;
}

}  // namespace granflow::rheology::testing
