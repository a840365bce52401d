// Symmetric 3x3 tensor: the strain rate D and the stress T of the rheology.
#pragma once

#include <array>

namespace granflow::rheology {

// Six independent components of a symmetric tensor. Plain aggregate so the solver can fill it
// per cell without allocation or construction cost.
struct SymmetricTensor {
  double xx{0.0}, yy{0.0}, zz{0.0}, xy{0.0}, xz{0.0}, yz{0.0};
};

// D = sym(grad u) ([YS] Eq. 4); the same type also carries stress tensors.
using StrainRate = SymmetricTensor;

// 2D planar flow in the x-y plane: D_zz = 0 and no out-of-plane shear.
constexpr StrainRate planar_strain_rate(double d_xx, double d_yy, double d_xy) noexcept {
  return {d_xx, d_yy, 0.0, d_xy, 0.0, 0.0};
}

// Axisymmetric (r, z) flow: r maps to x, z to y, and the hoop rate D_thth = u_r / r is the zz
// entry, so that the invariants see the full 3D deformation of the wedge ([YS] Sec. 4).
constexpr StrainRate axisymmetric_strain_rate(double d_rr, double d_zz, double d_rz,
                                              double hoop_rate) noexcept {
  return {d_rr, d_zz, hoop_rate, d_rz, 0.0, 0.0};
}

constexpr SymmetricTensor operator+(const SymmetricTensor& a, const SymmetricTensor& b) noexcept {
  return {a.xx + b.xx, a.yy + b.yy, a.zz + b.zz, a.xy + b.xy, a.xz + b.xz, a.yz + b.yz};
}

constexpr SymmetricTensor operator-(const SymmetricTensor& a, const SymmetricTensor& b) noexcept {
  return {a.xx - b.xx, a.yy - b.yy, a.zz - b.zz, a.xy - b.xy, a.xz - b.xz, a.yz - b.yz};
}

constexpr SymmetricTensor operator*(double s, const SymmetricTensor& a) noexcept {
  return {s * a.xx, s * a.yy, s * a.zz, s * a.xy, s * a.xz, s * a.yz};
}

constexpr SymmetricTensor isotropic_tensor(double value) noexcept {
  return {value, value, value, 0.0, 0.0, 0.0};
}

constexpr double trace(const SymmetricTensor& a) noexcept { return a.xx + a.yy + a.zz; }

// A : B = sum_ij A_ij B_ij (equals tr(A B) for symmetric tensors).
constexpr double double_contraction(const SymmetricTensor& a, const SymmetricTensor& b) noexcept {
  return a.xx * b.xx + a.yy * b.yy + a.zz * b.zz +
         2.0 * (a.xy * b.xy + a.xz * b.xz + a.yz * b.yz);
}

constexpr double determinant(const SymmetricTensor& a) noexcept {
  return a.xx * (a.yy * a.zz - a.yz * a.yz) - a.xy * (a.xy * a.zz - a.yz * a.xz) +
         a.xz * (a.xy * a.yz - a.yy * a.xz);
}

constexpr SymmetricTensor deviatoric(const SymmetricTensor& a) noexcept {
  const double mean = trace(a) / 3.0;
  return {a.xx - mean, a.yy - mean, a.zz - mean, a.xy, a.xz, a.yz};
}

// Principal values in ascending order (cyclic Jacobi rotations: accurate also for repeated
// eigenvalues, which the triaxial states of [YS] Table 1 have). Used by the Mohr-Coulomb yield
// function, not on the viscosity path.
std::array<double, 3> principal_values(const SymmetricTensor& a);

}  // namespace granflow::rheology
