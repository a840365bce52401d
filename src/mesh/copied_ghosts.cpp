#include "mesh/copied_ghosts.hpp"

#include "mesh/obstacles.hpp"
#include "mesh/side_ghosts.hpp"

namespace granflow {

void fill_copied_ghosts(const Grid& grid, const Field* blocked, Field& f) {
  f.scatter_to_local();
  FieldArray a = local_array(grid, f);
  mirror_into_blocked(grid, blocked, a.volume(), 1.0);
  fill_side_ghosts(grid, a.volume(), [](Side, double, double first) { return first; });
}

}  // namespace granflow
