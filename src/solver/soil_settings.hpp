#pragma once
// Settings of the two-phase (soil and air) model, filled from the case file.
#include <optional>
#include <string>
#include <vector>

#include "models/interface/initial_shapes.hpp"
#include "models/interface/initial_shapes_3d.hpp"
#include "models/mixture/mixture_interpolation.hpp"
#include "models/rheology/parameters.hpp"
#include "models/rheology/soil_materials.hpp"

namespace granflow {

enum class YieldPressure { cell, face, lithostatic_floor };
enum class StrainRateAt { cell, face };
enum class FaceFraction { cells, face };

// A soil beyond the rheology's own ([[soil.materials]]): the rheology's regularisation, and its own
// yield surface, friction law, strength and density (rheology.density, rho_s), each the rheology's
// unless given.
struct SoilMaterial {
  std::string name;
  rheology::RheologyParameters rheology;
};

struct SoilSettings {
  double air_density = 1.0;
  double air_viscosity = 1.8e-5;   // Pa s
  double soil_density = 2650.0;
  double soil_viscosity = 1e-3;    // Pa s, a Newtonian dense phase (water) when no rheology is given
  double surface_tension = 0.0;    // sigma, N/m, of the soil-air interface; 0: none
  double contact_angle = 90.0;     // theta, degrees through the soil, where the interface meets a wall side
  std::optional<rheology::RheologyParameters> rheology;  // granular soil
  mixture::MixtureInterpolation density_mixing;
  mixture::MixtureInterpolation viscosity_mixing;
  std::vector<interface::Shape> initial_soil;
  // On a mesh of layers: these, and initial_soil's shapes extruded across the whole depth.
  std::vector<interface::Shape3> initial_soil_3d;
  std::vector<SoilMaterial> materials;  // soils other than the rheology's own, carried with the soil
  // Per initial shape as listed, its soil: 0 the rheology's own, k materials[k - 1]. Where shapes
  // overlap, the last listed holds the point.
  std::vector<int> initial_material;
  // Per initial shape as listed, whether it is a solid (initial_soil_3d) or a planar shape (initial_soil).
  std::vector<bool> initial_shape_is_solid;
  // Whether some material's density is not soil_density: the mixture's density then follows the
  // cells' shares (otherwise the one-density forms run, to the bit).
  // On a mesh of layers from z_lower to z_upper: every initial shape as a solid, the planar ones
  // extruded across the whole depth, in the order listed (settings that do not record it, built in
  // code: the solids first).
  bool has_initial_shapes() const { return !initial_soil.empty() || !initial_soil_3d.empty(); }
  std::vector<interface::Shape3> initial_solids(double z_lower, double z_upper) const {
    std::vector<interface::Shape3> solids;
    auto extruded = [&](const interface::Shape& s) { return interface::Extrusion{s, z_lower, z_upper}; };
    if (initial_shape_is_solid.size() != initial_soil_3d.size() + initial_soil.size()) {
      solids = initial_soil_3d;
      for (const auto& s : initial_soil) solids.push_back(extruded(s));
      return solids;
    }
    size_t solid = 0, planar = 0;
    for (const bool is_solid : initial_shape_is_solid)
      if (is_solid) solids.push_back(initial_soil_3d[solid++]);
      else solids.push_back(extruded(initial_soil[planar++]));
    return solids;
  }
  bool materials_differ_in_density() const {
    for (const auto& m : materials)
      if (m.rheology.density != soil_density) return true;
    return false;
  }
  double interface_courant = 0.45;  // largest Courant number of one VoF sweep (< 0.5 for boundedness)
  bool displacement = true;         // carry the Eulerian displacement and strain ([VoF] Eq. 16); the case
                                    // file turns it on where there is a rheology (soil.displacement)
  double failure_strain = 0.3;      // ||e|| of the failure line ([VoF] Sec. 4)
  // Pressure entering the yield stress ([VoF] Sec. 2.2: the solver's own, clipped at zero):
  // - cell: the pressure at the cell centre, one viscosity per cell, faces take the mean of two cells';
  // - face: each face's viscosity from the pressure on that face (mean of its two cells', or the
  //   hydrostatic extrapolation to a wall), so that a layer one cell thick at the surface, whose centre
  //   pressure is about zero, still rubs on the soil below with the friction its weight gives;
  // - lithostatic_floor: the cell pressure, but at least the weight of the soil above the cell in its
  //   column (rho_s g depth).
  YieldPressure yield_pressure = YieldPressure::cell;
  // Strain rate in the face viscosities (with yield_pressure = face): each side's cell centre rate
  // (cell), or the rate on the face itself (face), the one its viscous stress multiplies.
  StrainRateAt strain_rate = StrainRateAt::cell;
  // Soil fraction of the mixture in the face viscosities (with strain_rate = face): each side its own
  // cell's, the face taking the mean of the two viscosities (cells), or the face's own, the mean of
  // the two cells' c, in one evaluation (face). With `face` a face between soil and air carries the
  // soil's plastic viscosity at the face's pressure: air in contact with the soil sticks to it.
  FaceFraction face_fraction = FaceFraction::cells;
};

}  // namespace granflow
