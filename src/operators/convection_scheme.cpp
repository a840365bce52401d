#include "operators/convection_scheme.hpp"

namespace granflow {
bool parse_convection_scheme(std::string_view name, ConvectionScheme& out) {
  if (name == "upwind") out = ConvectionScheme::upwind;
  else if (name == "central") out = ConvectionScheme::central;
  else if (name == "blended") out = ConvectionScheme::blended;
  else if (name == "quick") out = ConvectionScheme::quick;
  else return false;
  return true;
}
}  // namespace granflow
