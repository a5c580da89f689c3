#include "input/mesh_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

#include "core/error.hpp"

namespace penink {
namespace {

using Point3 = CGAL::Simple_cartesian<double>::Point_3;
using Polygon = std::vector<std::size_t>;

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Index of `name` in names, appended when new.
std::uint32_t material_index(std::vector<std::string>& names, const std::string& name) {
    auto it = std::find(names.begin(), names.end(), name);
    if (it != names.end()) return std::uint32_t(it - names.begin());
    names.push_back(name);
    return std::uint32_t(names.size() - 1);
}

// Fan-triangulates the soup; face_material (one per polygon, may be empty) names materials.
TriangleMesh build_mesh(const std::vector<Point3>& pts, const std::vector<Polygon>& polys,
                        const std::vector<std::string>& face_material) {
    TriangleMesh m;
    m.positions.reserve(pts.size());
    for (const auto& p : pts) m.positions.emplace_back(float(p.x()), float(p.y()), float(p.z()));
    const bool named = face_material.size() == polys.size();
    if (!named) m.material_names.push_back("default");
    for (std::size_t f = 0; f < polys.size(); ++f) {
        const Polygon& poly = polys[f];
        std::uint32_t mat = named ? material_index(m.material_names, face_material[f]) : 0;
        for (std::size_t k = 1; k + 1 < poly.size(); ++k) {
            if (poly[0] >= pts.size() || poly[k] >= pts.size() || poly[k + 1] >= pts.size()) continue;
            m.triangles.emplace_back(unsigned(poly[0]), unsigned(poly[k]), unsigned(poly[k + 1]));
            m.material.push_back(mat);
        }
    }
    if (m.material_names.empty()) m.material_names.push_back("default");
    return m;
}

// Every coordinate finite and within max_mesh_coordinate, else Error("input", path, ...) naming
// the first vertex (from 1, in file order) that is not.
void check_coordinates(const std::vector<Point3>& pts, const std::string& path) {
    for (std::size_t i = 0; i < pts.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            const double c = pts[i][k];
            if (std::isfinite(c) && std::abs(c) <= max_mesh_coordinate) continue;
            char text[48];
            std::snprintf(text, sizeof text, "%g", c);
            throw Error("input", path, "vertex " + std::to_string(i + 1) + " has coordinate " + text +
                                           ", out of range (mesh coordinates must be finite and within +-1e9)");
        }
}

}  // namespace

std::vector<std::string> scan_obj_face_materials(const std::string& obj_text) {
    std::vector<std::string> out;
    std::string current = "default";
    std::istringstream in(obj_text);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream ls(line);
        std::string key;
        if (!(ls >> key)) continue;
        if (key == "usemtl") {
            std::string name;
            std::getline(ls >> std::ws, name);
            while (!name.empty() && std::isspace(static_cast<unsigned char>(name.back()))) name.pop_back();
            current = name.empty() ? "default" : name;
        } else if (key == "f") {
            out.push_back(current);
        }
    }
    return out;
}

void weld_mesh(TriangleMesh& mesh) {
    std::map<std::tuple<float, float, float>, unsigned> index;
    std::vector<unsigned> remap(mesh.positions.size());
    std::vector<glm::vec3> pos;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3& p = mesh.positions[i];
        auto [it, fresh] = index.emplace(std::make_tuple(p.x, p.y, p.z), unsigned(pos.size()));
        if (fresh) pos.push_back(p);
        remap[i] = it->second;
    }
    std::vector<glm::uvec3> tris;
    std::vector<std::uint32_t> mats;
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        glm::uvec3 t(remap[mesh.triangles[f].x], remap[mesh.triangles[f].y], remap[mesh.triangles[f].z]);
        if (t.x == t.y || t.y == t.z || t.x == t.z) continue;
        tris.push_back(t);
        mats.push_back(mesh.material[f]);
    }
    mesh.positions.swap(pos);
    mesh.triangles.swap(tris);
    mesh.material.swap(mats);
}

TriangleMesh read_mesh(const std::string& path, bool weld) {
    const std::string ext = lower_extension(path);
    if (ext != ".obj" && ext != ".ply" && ext != ".off")
        throw Error("input", path, "unsupported mesh format \"" + ext + "\" (use .obj, .ply or .off)");
    if (!std::filesystem::is_regular_file(path)) throw Error("input", path, "no such file");
    std::vector<Point3> pts;
    std::vector<Polygon> polys;
    bool ok = false;
    try {
        ok = CGAL::IO::read_polygon_soup(path, pts, polys, CGAL::parameters::verbose(false));
    } catch (const std::exception&) {
        ok = false;
    }
    // CGAL reports a file with vertices but no faces as a failure: that is a mesh without triangles.
    if (!ok && (pts.empty() || !polys.empty())) throw Error("input", path, "not a mesh (cannot read OBJ/PLY/OFF)");
    check_coordinates(pts, path);
    std::vector<std::string> mats;
    if (ext == ".obj") mats = scan_obj_face_materials(read_text(path));
    TriangleMesh m = build_mesh(pts, polys, mats);
    if (weld) weld_mesh(m);
    if (m.triangles.empty()) throw Error("input", path, "mesh has no triangles");
    m.source = path;
    return m;
}

}  // namespace penink
