#pragma once
// The finite-volume operator sum_f K_f (p_P - p_N) over a cell's faces, assembled into a matrix of the
// grid's star-stencil DMDA: the pressure equation's ([VoF] Eqs. 28-30), and any diffusion of a cell
// scalar. K_f is the face's conductance (coefficient times area over the distance between the centres);
// a boundary face adds its own conductance to the diagonal (a value held at the face: the caller puts
// K_b times that value into the right-hand side) or nothing (no flux).
//
// On a planar or axisymmetric mesh a row holds P, then the east, west, north and south neighbours that
// exist; on a mesh of layers the back and front ones too. The grid's own geometry is not read: the
// callables hold it. The momentum equation's rows have the same pattern with a diagonal of their own.
#include <petscmat.h>

#include "mesh/grid.hpp"

namespace granflow {

// The rows a_P x_P - sum_nb a_nb x_nb of the owned cells, a_nb from interior(axis, sign, i, j, k) for
// each neighbour in the domain (east, west, north, south, then back and front), and a_P from
// diagonal(i, j, k, sum), sum being the a_nb of the row plus what boundary(axis, sign, i, j, k) says each
// face on the domain's boundary adds. Beyond a periodic side the neighbour is a cell of the other end.
template <class Interior, class Boundary, class Diagonal>
void assemble_star_rows(const Grid& g, Mat A, Interior interior, Boundary boundary, Diagonal diagonal) {
  const auto& b = g.owned();
  const int dimension = g.dimension();
  constexpr int axis_of[6] = {0, 0, 1, 1, 2, 2};
  constexpr int sign_of[6] = {1, -1, 1, -1, 1, -1};
  for (int k = b.zs; k < b.ze(); ++k)
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i) {
        MatStencil row{k, j, i, 0};
        MatStencil cols[7];
        double vals[7];
        int n = 1;
        cols[0] = row;
        double sum = 0.0;
        for (int f = 0; f < 2 * dimension; ++f) {
          const int axis = axis_of[f], sign = sign_of[f];
          const int in = i + (axis == 0 ? sign : 0), jn = j + (axis == 1 ? sign : 0), kn = k + (axis == 2 ? sign : 0);
          if (g.outside(in, jn, kn)) {
            sum += boundary(axis, sign, i, j, k);
            continue;
          }
          const double a = interior(axis, sign, i, j, k);
          sum += a;
          cols[n] = MatStencil{kn, jn, in, 0};
          vals[n++] = -a;
        }
        vals[0] = diagonal(i, j, k, sum);
        PetscCallAbort(PETSC_COMM_SELF, MatSetValuesStencil(A, 1, &row, n, cols, vals, INSERT_VALUES));
      }
  PetscCallAbort(g.comm(), MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCallAbort(g.comm(), MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
}

// The face Laplacian: interior(axis, sign, i, j, k) is K of the face of cell (i, j, k) on its `sign`
// side along `axis`; boundary(axis, sign, i, j, k) what a face on the domain's boundary adds to the
// diagonal; the diagonal is the sum.
template <class Interior, class Boundary>
void assemble_face_laplacian(const Grid& g, Mat A, Interior interior, Boundary boundary) {
  assemble_star_rows(g, A, interior, boundary, [](int, int, int, double sum) { return sum; });
}

}  // namespace granflow
