#pragma once
// Euler-Almansi strain from the Eulerian displacement ([VoF] Eqs. 13-14): F = I - grad u,
// G = F^-1, e = (I - G G^T)/2. Planar: the out-of-plane stretch is one, so e_zz = 0, but the
// deviatoric part still carries -tr(e)/3 in zz. The norm is the Frobenius norm sqrt(e_dev : e_dev)
// (the measure whose 0.3 contour is the failure line of [VoF] Sec. 4).
namespace granflow::strain {

struct DisplacementGradient {
  double xx = 0, xy = 0, yx = 0, yy = 0;  // d u_i / d x_j, i = row
};

struct AlmansiStrain {
  double xx = 0, xy = 0, yy = 0;  // zz = 0 in plane strain
};

// Returns false (and a zero strain) where F is singular, which only a corrupted displacement gives.
bool almansi_strain(const DisplacementGradient& grad_u, AlmansiStrain& e);
double deviatoric_norm(const AlmansiStrain& e);

}  // namespace granflow::strain
