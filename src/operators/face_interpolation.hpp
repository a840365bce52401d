#pragma once
// Interpolation of a cell property (viscosity) to a face.
namespace granflow {

enum class FaceViscosity { harmonic, arithmetic };

// Harmonic mean: the face flux of a layered medium is exact for a viscosity jump at the face, so a
// 1e8 contrast does not let the stiff side leak its viscosity into the soft one.
inline double face_mean(FaceViscosity kind, double a, double b) {
  if (kind == FaceViscosity::arithmetic) return 0.5 * (a + b);
  const double s = a + b;
  return s > 0.0 ? 2.0 * a * b / s : 0.0;
}

}  // namespace granflow
