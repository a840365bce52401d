#pragma once
// Whole-domain copies of distributed fields on rank 0 (for writers and samplers, io/field_sample.hpp).
#include <vector>

#include "mesh/field.hpp"

namespace granflow {

// Owned values of `field` in natural order (index j * nx + i) on rank 0; empty on other ranks.
std::vector<double> gather_to_root(const Grid& grid, const Field& field);
// The same from a global vector of the grid's field layout.
std::vector<double> gather_to_root(const Grid& grid, Vec global);

}  // namespace granflow
