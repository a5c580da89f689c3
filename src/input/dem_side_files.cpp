// Side file names of a DEM (dem_side_files.hpp).
#include "input/dem_side_files.hpp"

#include <filesystem>

namespace penink {

std::vector<std::string> dem_side_files(const std::string& path) {
    const std::filesystem::path p(path);
    const std::string ext = p.extension().string();  // ".tif"
    const std::string stem = path.substr(0, path.size() - ext.size());
    std::vector<std::string> names = {path + ".aux.xml", path + ".ovr", path + ".msk", stem + ".prj", stem + ".PRJ",
                                      stem + ".aux.xml", stem + ".wld", stem + ".WLD"};
    if (ext.size() >= 3) {
        const std::string e = ext.substr(1);
        const std::string short_form = std::string(1, e.front()) + e.back() + "w";
        for (const std::string& w : {short_form, e + "w"}) {
            std::string up = w;
            for (char& c : up) c = char(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
            std::string low = w;
            for (char& c : low) c = char(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
            names.push_back(stem + "." + low);
            names.push_back(stem + "." + up);
        }
    }
    return names;
}

}  // namespace penink
