// The files GDAL may read beside a DEM `path` (its georeference and metadata): the world file in
// each of its forms (PATH minus extension plus the extension's first and last letters and "w",
// plus the whole extension and "w", plus ".wld"; both letter cases), the .prj, the .aux.xml (as
// PATH.aux.xml and stem.aux.xml), and the .ovr and .msk. They are inputs: no output may replace
// them (core/input_files.hpp). Names only; whether each exists is not checked.
#pragma once
#include <string>
#include <vector>

namespace penink {

std::vector<std::string> dem_side_files(const std::string& path);

}  // namespace penink
