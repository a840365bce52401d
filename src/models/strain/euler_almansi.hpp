#pragma once
// Euler-Almansi strain from the Eulerian displacement ([VoF] Eqs. 13-14): F = I - grad u,
// G = F^-1, e = (I - G G^T)/2. Planar: the out-of-plane stretch is one, so e_zz = 0, but the
// deviatoric part still carries -tr(e)/3 in zz. Axisymmetric (x = r, y = z): grad u has the hoop
// entry u_r / r, so F_thth = 1 - u_r / r and e_thth = (1 - 1/F_thth^2)/2 takes the place of e_zz.
// The norm is the Frobenius norm sqrt(e_dev : e_dev) (the measure whose 0.3 contour is the failure
// line of [VoF] Sec. 4).
namespace granflow::strain {

struct DisplacementGradient {
  double xx = 0, xy = 0, yx = 0, yy = 0;  // d u_i / d x_j, i = row
  double hoop = 0;                        // u_r / r (axisymmetric), 0 in planar
};

struct AlmansiStrain {
  double xx = 0, xy = 0, yy = 0;
  double hoop = 0;  // e_thth (axisymmetric); the out-of-plane e_zz = 0 in plane strain
};

// Returns false (and a zero strain) where F is singular, which only a corrupted displacement gives.
bool almansi_strain(const DisplacementGradient& grad_u, AlmansiStrain& e);
double deviatoric_norm(const AlmansiStrain& e);

// In 3D: the whole displacement gradient, g[i][j] = d u_i / d x_j, and the whole symmetric strain.
struct DisplacementGradient3 {
  double g[3][3] = {};
};
struct AlmansiStrain3 {
  double xx = 0, yy = 0, zz = 0, xy = 0, xz = 0, yz = 0;
};
bool almansi_strain(const DisplacementGradient3& grad_u, AlmansiStrain3& e);
double deviatoric_norm(const AlmansiStrain3& e);

}  // namespace granflow::strain
