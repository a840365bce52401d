#include "models/rheology/soil_materials.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace granflow::rheology {

RheologyParameters with_strength(const RheologyParameters& base, const MaterialStrength& strength) {
  RheologyParameters p = base;
  p.friction_angle_deg = strength.friction_angle_deg;
  p.cohesion = strength.cohesion;
  if (strength.model) p.model = *strength.model;
  return p;
}

SoilMaterials::SoilMaterials(const RheologyParameters& base, const std::vector<MaterialStrength>& others) {
  if (others.size() + 1 > std::size_t(max_count))
    throw std::invalid_argument(fmt::format("{} soil materials, more than the {} a case may have", others.size() + 1, max_count));
  materials_.reserve(others.size() + 1);
  materials_.emplace_back(base);
  for (std::size_t k = 0; k < others.size(); ++k) {
    const RheologyParameters p = with_strength(base, others[k]);
    if (auto error = validate(p)) throw std::invalid_argument(fmt::format("soil material {}: {}", k + 1, *error));
    materials_.emplace_back(p);
  }
  for (const auto& m : materials_) needs_lode_angle_ = needs_lode_angle_ || m.needs_lode_angle();
}

}  // namespace granflow::rheology
