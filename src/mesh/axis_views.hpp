#pragma once
// Read access, as arrays [k][j][i], to a quantity held as one field per axis (the velocity's
// components, the faces normal to each axis): view[a] for the first `count` axes, null beyond.
#include <memory>
#include <optional>
#include <type_traits>

#include "mesh/field.hpp"

namespace granflow {

class AxisViews {
 public:
  // The local (ghosted) arrays, or the global ones (owned cells only).
  AxisViews(const Grid& g, const std::unique_ptr<Field>* fields, int count, bool global = false) {
    for (int a = 0; a < count; ++a)
      view[a] = arrays_[a].emplace(g.field_dm(), global ? fields[a]->global() : fields[a]->local()).volume();
  }
  // One per axis of the mesh.
  AxisViews(const Grid& g, const std::unique_ptr<Field> (&fields)[3]) : AxisViews(g, fields, g.dimension()) {}
  // The local arrays of field(a) for each axis a of the mesh (a class's fields handed out one by one).
  template <class Get>
    requires std::is_invocable_r_v<const Field&, Get, int>
  AxisViews(const Grid& g, Get field) {
    for (int a = 0; a < g.dimension(); ++a) view[a] = arrays_[a].emplace(g.field_dm(), field(a).local()).volume();
  }
  AxisViews(const AxisViews&) = delete;
  AxisViews& operator=(const AxisViews&) = delete;

  VolumeView view[3] = {};

 private:
  std::optional<ConstFieldArray> arrays_[3];
};

}  // namespace granflow
