#include "input/mesh_subdivision.hpp"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/subdivision_method_3.h>

#include "core/error.hpp"

namespace penink {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

Mesh to_surface_mesh(const TriangleMesh& in) {
    Mesh m;
    std::vector<Mesh::Vertex_index> v;
    v.reserve(in.positions.size());
    for (const glm::vec3& p : in.positions) v.push_back(m.add_vertex(Kernel::Point_3(p.x, p.y, p.z)));
    for (const glm::uvec3& t : in.triangles)
        if (m.add_face(v[t.x], v[t.y], v[t.z]) == Mesh::null_face())
            throw Error("input", in.source, "cannot subdivide: the mesh is not an oriented manifold");
    return m;
}

}  // namespace

void loop_subdivide(TriangleMesh& mesh, int iterations) {
    if (iterations <= 0) return;
    if (mesh.material_names.size() > 1)
        throw Error("input", mesh.source, "cannot subdivide a mesh with several materials");
    Mesh m = to_surface_mesh(mesh);
    CGAL::Subdivision_method_3::Loop_subdivision(m, CGAL::parameters::number_of_iterations(iterations));
    mesh.positions.clear(), mesh.triangles.clear();
    std::vector<std::uint32_t> index(m.number_of_vertices() + m.number_of_removed_vertices(), 0);
    for (Mesh::Vertex_index v : m.vertices()) {
        index[v] = std::uint32_t(mesh.positions.size());
        const Kernel::Point_3& p = m.point(v);
        mesh.positions.emplace_back(float(p.x()), float(p.y()), float(p.z()));
    }
    for (Mesh::Face_index f : m.faces()) {
        glm::uvec3 tri;
        int k = 0;
        for (Mesh::Vertex_index v : CGAL::vertices_around_face(m.halfedge(f), m)) tri[k++] = index[v];
        mesh.triangles.push_back(tri);
    }
    mesh.material.assign(mesh.triangles.size(), 0);
}

}  // namespace penink
