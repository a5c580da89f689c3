#include "input/mesh_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

#include "core/error.hpp"
#include "core/input_files.hpp"
#include "core/printable_text.hpp"

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

// An OBJ's vertex lines ("v x y z") checked before CGAL reads them: its reader stops at a
// coordinate such as "nan" or "inf" and reports the file as having no faces, so a coordinate that
// reads as a non-finite number is named here (vertex numbers from 1, in file order).
void check_obj_vertices(const std::string& text, const std::string& path) {
    std::size_t vertex = 0;
    for (std::size_t at = 0; at < text.size();) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        const std::size_t start = text.find_first_not_of(" \t", at);
        if (start < end && (text.compare(start, 2, "v ") == 0 || text.compare(start, 2, "v\t") == 0)) {
            ++vertex;
            std::size_t i = start + 2;
            for (int k = 0; k < 3; ++k) {
                i = text.find_first_not_of(" \t", i);
                if (i >= end) break;
                const std::size_t stop = std::min(text.find_first_of(" \t\r\n", i), end);
                const std::string token = text.substr(i, stop - i);
                const double c = std::strtod(token.c_str(), nullptr);
                if (!std::isfinite(c))
                    throw Error("input", path, "vertex " + std::to_string(vertex) + " has coordinate " + printable_text(token, 20) +
                                                   ", out of range (mesh coordinates must be finite and within +-1e9)");
                i = stop;
            }
        }
        at = end + 1;
    }
}

// The text of an ASCII OFF file read into a polygon soup (CGAL's OFF reader reads past its arrays
// on a colour line shorter than the header promises, found by fuzzing): an optional header
// keyword ([ST][C][N]OFF; 4OFF, nOFF and binary OFF are refused), the counts nv nf [ne], nv
// vertex lines (x y z first, anything after ignored: normals, colours, texture coordinates), nf
// face lines (k, then k indices; a colour after them ignored). # starts a comment. Fails
// "not a mesh (OFF: WHAT)".
void read_off(const std::string& path, std::vector<Point3>& pts, std::vector<Polygon>& polys) {
    std::ifstream in(path, std::ios::binary);
    auto bad = [&path](const std::string& what) { throw Error("input", path, "not a mesh (OFF: " + what + ")"); };
    std::string line;
    int n = 0;
    // The next line with something on it, comments cut; false at the end.
    auto next = [&](std::istringstream& words) {
        while (std::getline(in, line)) {
            ++n;
            if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
            if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
            words.clear(), words.str(line);
            return true;
        }
        return false;
    };
    std::istringstream words;
    if (!next(words)) bad("empty file");
    std::string first;
    words >> first;
    if (first.size() >= 3 && first.substr(first.size() - 3) == "OFF") {
        const std::string prefix = first.substr(0, first.size() - 3);
        if (prefix.find_first_not_of("STCN") != std::string::npos) bad("\"" + printable_text(first, 20) + "\" files are not read");
        std::string more;
        if (words >> more) {
            if (more == "BINARY") bad("binary files are not read");
            words.clear(), words.str(line.substr(line.find(first) + first.size()));  // counts on the keyword's line
        } else if (!next(words)) {
            bad("no counts");
        }
    } else {
        words.clear(), words.str(line);
    }
    std::uint64_t nv = 0, nf = 0;
    if (!(words >> nv >> nf)) bad("line " + std::to_string(n) + ": expected the vertex and face counts");
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (!ec && nv + nf > size / 2)  // a line of a digit and a newline at least each
        bad("declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) + " faces, more than its " +
            std::to_string(size) + " bytes hold");
    pts.reserve(std::size_t(nv));
    for (std::uint64_t i = 0; i < nv; ++i) {
        double x = 0, y = 0, z = 0;
        if (!next(words) || !(words >> x >> y >> z)) bad("line " + std::to_string(n) + ": expected vertex x y z");
        pts.emplace_back(x, y, z);
    }
    polys.reserve(std::size_t(nf));
    for (std::uint64_t i = 0; i < nf; ++i) {
        std::uint64_t k = 0;
        if (!next(words) || !(words >> k) || k > nv + 2) bad("line " + std::to_string(n) + ": expected a face");
        Polygon p(static_cast<std::size_t>(k));
        for (std::size_t& v : p)
            if (!(words >> v)) bad("line " + std::to_string(n) + ": expected " + std::to_string(k) + " vertex indices");
        polys.push_back(std::move(p));
    }
}

// CGAL's PLY reader writes through the last element of an empty list on a `property` line before
// any `element` line (a crash), and reserves what the header declares: the header is checked
// first. Lines up to end_header: "ply", then format, comment, obj_info, element NAME COUNT and
// property lines, a property only after an element; the elements declared no more than the bytes
// after the header (each takes one at least). Fails "not a mesh (PLY header: WHAT)".
void check_ply_header(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    auto bad = [&path](const std::string& what) { throw Error("input", path, "not a mesh (PLY header: " + what + ")"); };
    std::string line;
    std::uint64_t header_bytes = 0, elements = 0;
    bool element = false, ended = false, xyz_ok = true;
    std::string element_name;
    for (int n = 1; !ended && n <= 10000 && std::getline(in, line); ++n) {
        header_bytes += line.size() + 1;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream words(line);
        std::string key;
        words >> key;
        if (n == 1) {
            if (key != "ply") bad("no \"ply\" line");
        } else if (key == "element") {
            std::uint64_t count = 0;
            if (!(words >> element_name >> count)) bad("line " + std::to_string(n) + ": element without a name and count");
            elements += count;
            element = true;
        } else if (key == "property") {
            if (!element) bad("line " + std::to_string(n) + ": property before any element");
            std::string type, name;
            words >> type >> name;
            // CGAL reads a vertex's x, y, z as float or double whatever their type (a crash)
            if (element_name == "vertex" && (name == "x" || name == "y" || name == "z"))
                xyz_ok = xyz_ok && (type == "float" || type == "float32" || type == "double" || type == "float64");
        } else if (key == "end_header") {
            ended = true;
        } else if (key != "format" && key != "comment" && key != "obj_info") {
            bad("line " + std::to_string(n) + ": unknown keyword \"" + printable_text(key, 20) + "\"");
        }
    }
    if (!ended) bad("no end_header");
    if (!xyz_ok) bad("vertex x, y and z must be float or double numbers (CGAL reads no other)");
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (!ec && elements > size - std::min<std::uintmax_t>(size, header_bytes))
        bad("declares " + std::to_string(elements) + " elements, more than the " +
            std::to_string(size - std::min<std::uintmax_t>(size, header_bytes)) + " bytes after it hold");
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
    check_input_file("input", path);  // local, a regular file (no FIFO, device or folder)
    if (ext == ".ply") check_ply_header(path);
    const std::string obj_text = ext == ".obj" ? read_text(path) : std::string();
    if (ext == ".obj") check_obj_vertices(obj_text, path);
    std::vector<Point3> pts;
    std::vector<Polygon> polys;
    bool ok = false;
    if (ext == ".off") {
        read_off(path, pts, polys);
        ok = !polys.empty();
    } else {
        try {
            ok = CGAL::IO::read_polygon_soup(path, pts, polys, CGAL::parameters::verbose(false));
        } catch (const std::exception&) {
            ok = false;
        }
    }
    // CGAL reports a file with vertices but no faces as a failure: that is a mesh without triangles.
    if (!ok && (pts.empty() || !polys.empty())) throw Error("input", path, "not a mesh (cannot read OBJ/PLY/OFF)");
    check_coordinates(pts, path);
    std::vector<std::string> mats;
    if (ext == ".obj") mats = scan_obj_face_materials(obj_text);
    TriangleMesh m = build_mesh(pts, polys, mats);
    if (weld) weld_mesh(m);
    if (m.triangles.empty()) throw Error("input", path, "mesh has no triangles");
    m.source = path;
    return m;
}

}  // namespace penink
