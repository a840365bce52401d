#include "io/case_advice.hpp"

namespace granflow {

std::vector<std::string> case_advice(const CaseConfig& config) {
  std::vector<std::string> advice;
  if (!config.soil || !config.soil->rheology) return advice;
  // The exponential regularisation ([VoF] Eq. 12) puts the soil at rest at up to m (3 alpha_phi p + k_c),
  // some 1e8 Pa s. Only the coupled solve with the face's own soil fraction holds such a pile next to
  // air (docs/method.md, "Known limitations"; docs/validation.md).
  const bool exponential = config.soil->rheology->regularisation == rheology::Regularisation::exponential;
  const bool holds_rest = config.flow.numerics.pressure_coupling == PressureCoupling::coupled &&
                          config.soil->face_fraction == FaceFraction::face;
  if (exponential && !holds_rest)
    advice.push_back(
        "soil.rheology.regularisation = \"exponential\" (viscosities up to some 1e8 Pa s) is held at rest next to "
        "air only with numerics.pressure_coupling = \"coupled\" and soil.face_fraction = \"face\"; with these "
        "numerics a pile may not come to rest (docs/method.md, \"Known limitations\"; the example of "
        "docs/case_file.md)");
  return advice;
}

}  // namespace granflow
