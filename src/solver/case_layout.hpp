#pragma once
// Laying a case out on its mesh: what only the mesh shows of the case (an obstacle one cell thick or
// holding no cell centre, open cells closed off, initial shapes that place no soil, a material that
// holds none), said as errors of the case file, and the obstacles' mask and the soil the shapes place.
#include <cstdint>
#include <string>
#include <vector>

#include "io/case_error.hpp"
#include "io/case_file.hpp"
#include "mesh/field.hpp"
#include "mesh/grid.hpp"

namespace granflow {

// What laying the case on the mesh finds is of the case: named with its file, as reading it is.
CaseError case_error(const CaseConfig& config, const std::string& text);

// The error of initial shapes that place no soil in any open cell.
CaseError no_initial_soil(const CaseConfig& config, const Grid& g, bool obstacles);

// Each soil material holds some soil once the shapes are laid out (volumes: the rheology's own soil,
// then each material's); throws CaseError naming the first that holds none.
void check_materials_hold_soil(const CaseConfig& config, const std::vector<double>& volumes);

// What laying out the obstacles finds: the blocked cells' count and hash (all ranks), and the mask
// gathered to rank 0 (empty elsewhere).
struct ObstacleLayout {
  long blocked_cells = 0;
  std::uint64_t hash = 0;
  std::vector<double> mask_on_root;
  // The cells of ridges one cell wide opened (mesh/thin_ridges.hpp), per obstacle (the last listed that
  // holds the cell's centre; empty when no obstacle lowers its ridges), and their volume.
  std::vector<long> ridge_cells_opened;
  double ridge_volume_opened = 0.0;
};

// The ridges one cell wide that laying out opened, said for the user ("" where none were): how many
// cells of which obstacles, and their volume.
std::string ridges_lowered(const ObstacleLayout& layout);

// Marks the cells of the case's obstacles into mask (mesh/obstacles.hpp) and checks the whole mask.
// Collective; every rank throws alike.
ObstacleLayout lay_out_obstacles(const Grid& g, const CaseConfig& config, Field& mask);

// The soil volume the initial shapes place in open cells, and what of them lies in blocked cells
// and is left out (all ranks' sums).
struct PlacedSoil {
  double in_open_cells = 0.0;
  double in_blocked_cells = 0.0;
};
PlacedSoil initial_soil_placed(const Grid& g, const CaseConfig& config, const Field* mask);

}  // namespace granflow
