#pragma once
// Face values of a convected quantity for the schemes a case can choose (upwind, central, blended,
// QUICK). Each scheme is a pure function of the upwind-upwind (UU), upwind (U) and downwind (D) cell
// values; the implicit part is always upwind and the difference is added as a deferred correction.
#include <string_view>

namespace granflow {

enum class ConvectionScheme { upwind, central, blended, quick };

// blending: weight of central differencing in the blended scheme ([VoF] Sec. 3 uses 0.7).
inline double face_value(ConvectionScheme scheme, double blending, double uu, double u, double d) {
  switch (scheme) {
    case ConvectionScheme::upwind: return u;
    case ConvectionScheme::central: return 0.5 * (u + d);
    case ConvectionScheme::blended: return blending * 0.5 * (u + d) + (1.0 - blending) * u;
    case ConvectionScheme::quick: return 0.75 * u + 0.375 * d - 0.125 * uu;  // Leonard (1979), uniform spacing
  }
  return u;
}

bool parse_convection_scheme(std::string_view name, ConvectionScheme& out);

}  // namespace granflow
