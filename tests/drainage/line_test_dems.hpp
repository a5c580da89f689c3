// The DEMs the drainage lines' part-by-part tests build on: volcano at its automatic factor and
// at factor 1, holed_hills (nodata holes) at factor 2, geographic jacksboro (a curvilinear UTM
// grid) at factor 1.
#pragma once
#include <string>
#include <vector>

#include "drainage/drainage_build.hpp"
#include "input/dem_reader.hpp"
#include "support/synthetic_terrain.hpp"

namespace penink {

struct LineTestDem {
    Terrain terrain;
    int factor = 1;
    std::string name;
};

inline std::vector<LineTestDem> line_test_dems() {
    std::vector<LineTestDem> out;
    const Terrain volcano = read_dem(PENINK_SOURCE_DIR "/examples/volcano.asc");
    out.push_back({volcano, drainage_resample_factor(volcano, DrainageOptions{}), "volcano_auto"});
    out.push_back({volcano, 1, "volcano_factor1"});
    out.push_back({holed_hills(), 2, "holes_factor2"});
    out.push_back({read_dem(PENINK_SOURCE_DIR "/examples/jacksboro.tif"), 1, "jacksboro_factor1"});
    return out;
}

}  // namespace penink
