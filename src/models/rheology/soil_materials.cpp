#include "models/rheology/soil_materials.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace granflow::rheology {

SoilMaterials::SoilMaterials(const RheologyParameters& base, const std::vector<RheologyParameters>& others) {
  if (others.size() + 1 > std::size_t(max_count))
    throw std::invalid_argument(fmt::format("{} soil materials, more than the {} a case may have", others.size() + 1, max_count));
  materials_.reserve(others.size() + 1);
  materials_.emplace_back(base);
  for (std::size_t k = 0; k < others.size(); ++k) {
    const RheologyParameters& p = others[k];
    if (auto error = validate(p)) throw std::invalid_argument(fmt::format("soil material {}: {}", k + 1, *error));
    // One regularisation for all: a point's mixed yield stress is regularised once, by the base's.
    if (p.regularisation != base.regularisation || p.regularisation_time != base.regularisation_time ||
        p.min_dynamic_viscosity != base.min_dynamic_viscosity || p.min_kinematic_viscosity != base.min_kinematic_viscosity ||
        p.max_kinematic_viscosity != base.max_kinematic_viscosity)
      throw std::invalid_argument(fmt::format("soil material {}: its regularisation is not the first soil's", k + 1));
    materials_.emplace_back(p);
  }
  for (const auto& m : materials_) needs_lode_angle_ = needs_lode_angle_ || m.needs_lode_angle();
}

}  // namespace granflow::rheology
