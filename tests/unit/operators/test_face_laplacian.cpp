// The face Laplacian sum_f K_f (p_P - p_N) on a mesh of layers: a variable-coefficient Poisson problem
// -div(k grad p) = f in the unit cube, with p held at zero on the sides through the boundary faces'
// conductances, converges at second order to the manufactured solution.
#include <gtest/gtest.h>
#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mesh/field.hpp"
#include "mesh/grid.hpp"
#include "mesh/petsc_handle.hpp"
#include "operators/face_laplacian.hpp"

namespace granflow {
namespace {

using std::numbers::pi;

// p = sin(pi x) sin(pi y) sin(pi z), k = 1 + x y z: f = -div(k grad p) = 3 pi^2 k p - grad k . grad p.
double exact(double x, double y, double z) { return std::sin(pi * x) * std::sin(pi * y) * std::sin(pi * z); }
double conductivity(double x, double y, double z) { return 1.0 + x * y * z; }
double source(double x, double y, double z) {
  const double sx = std::sin(pi * x), sy = std::sin(pi * y), sz = std::sin(pi * z);
  const double cx = std::cos(pi * x), cy = std::cos(pi * y), cz = std::cos(pi * z);
  return 3.0 * pi * pi * conductivity(x, y, z) * sx * sy * sz -
         pi * (y * z * cx * sy * sz + x * z * sx * cy * sz + x * y * sx * sy * cz);
}

// The largest error at the cell centres on n^3 cells.
double poisson_error(int n) {
  GridSpec spec;
  spec.cells = {n, n, n};
  const Grid g(PETSC_COMM_SELF, spec);
  OwnedMat A;
  PetscCallAbort(PETSC_COMM_SELF, DMCreateMatrix(g.matrix_dm(), A.put()));
  // k at the centre of the face of cell (i, j, k) on its `sign` side along `axis`.
  auto face_k = [&](int axis, int sign, int i, int j, int k) {
    double x = g.xc(i), y = g.yc(j), z = g.zc(k);
    const double half = 0.5 * sign * (axis == 0 ? g.dx(i) : axis == 1 ? g.dy(j) : g.dz(k));
    (axis == 0 ? x : axis == 1 ? y : z) += half;
    return conductivity(x, y, z);
  };
  auto width = [&](int axis, int i, int j, int k) { return axis == 0 ? g.dx(i) : axis == 1 ? g.dy(j) : g.dz(k); };
  assemble_face_laplacian(
      g, A,
      [&](int axis, int sign, int i, int j, int k) {
        const int in = i + (axis == 0 ? sign : 0), jn = j + (axis == 1 ? sign : 0), kn = k + (axis == 2 ? sign : 0);
        const double d = 0.5 * (width(axis, i, j, k) + width(axis, in, jn, kn));
        return face_k(axis, sign, i, j, k) * g.face_area(axis, i, j, k, 1.0) / d;
      },
      [&](int axis, int sign, int i, int j, int k) {  // p = 0 held on the face
        return face_k(axis, sign, i, j, k) * g.face_area(axis, i, j, k, 1.0) / (0.5 * width(axis, i, j, k));
      });
  Field p(g), rhs(g);
  {
    FieldArray r(g.field_dm(), rhs.global());
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) r.volume()[k][j][i] = source(g.xc(i), g.yc(j), g.zc(k)) * g.volume(i, j, k);
  }
  OwnedKsp ksp;
  PetscCallAbort(PETSC_COMM_SELF, KSPCreate(PETSC_COMM_SELF, ksp.put()));
  PetscCallAbort(PETSC_COMM_SELF, KSPSetOperators(ksp, A, A));
  PetscCallAbort(PETSC_COMM_SELF, KSPSetType(ksp, KSPCG));
  PC pc;
  PetscCallAbort(PETSC_COMM_SELF, KSPGetPC(ksp, &pc));
  PetscCallAbort(PETSC_COMM_SELF, PCSetType(pc, PCGAMG));
  PetscCallAbort(PETSC_COMM_SELF, KSPSetTolerances(ksp, 1e-12, 1e-50, PETSC_DEFAULT, 500));
  PetscCallAbort(PETSC_COMM_SELF, KSPSolve(ksp, rhs.global(), p.global()));
  KSPConvergedReason reason;
  PetscCallAbort(PETSC_COMM_SELF, KSPGetConvergedReason(ksp, &reason));
  EXPECT_GT(reason, 0) << "the solve did not converge on " << n << "^3 cells";
  double worst = 0.0;
  ConstFieldArray a(g.field_dm(), p.global());
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        worst = std::max(worst, std::abs(a.volume()[k][j][i] - exact(g.xc(i), g.yc(j), g.zc(k))));
  return worst;
}

TEST(FaceLaplacian, VariableCoefficientPoissonIn3dConvergesAtSecondOrder) {
  const double e8 = poisson_error(8), e16 = poisson_error(16), e32 = poisson_error(32);
  RecordProperty("errors", std::to_string(e8) + " " + std::to_string(e16) + " " + std::to_string(e32));
  EXPECT_GT(std::log2(e8 / e16), 1.8) << e8 << " -> " << e16;
  EXPECT_GT(std::log2(e16 / e32), 1.9) << e16 << " -> " << e32;
  EXPECT_LT(e32, 2e-3);
}

}  // namespace
}  // namespace granflow
