#pragma once
// A height map from a text file (`heights_file` of a height map): an ESRI ASCII grid (".asc"), as GIS
// tools export a digital elevation model. Its header gives `ncols`, `nrows`, `xllcorner` or
// `xllcenter`, `yllcorner` or `yllcenter`, `cellsize` (or `dx` and `dy`) and optionally
// `NODATA_value`, one key and its number a line in any case; then nrows x ncols heights, the first row
// the northernmost, separated by blanks. The grid's x is the mesh's x, its northing the mesh's z, and
// its heights the mesh's y (up). Values are taken at the cells' centres (`*corner`: the corner of the
// lower-left cell; `*center`: its centre).
#include <filesystem>
#include <string>

#include "models/interface/initial_shapes_3d.hpp"

namespace granflow {

// The map's nodes, origin and spacing (its bottom left unset). Throws CaseError naming `key_path` and the
// file where it cannot be read, and the file and line where the header or a height is wrong or a
// height is missing (NODATA: an elevation model with holes must be filled first).
interface::HeightMap read_height_map_file(const std::filesystem::path& file, const std::string& key_path);

}  // namespace granflow
