// Mesh reader: OBJ with usemtl groups, OFF and PLY through CGAL, welding, exact errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "input/mesh_reader.hpp"

using namespace penink;

namespace {

std::string temp_file(const std::string& name, const std::string& text) {
    std::string path = testing::TempDir() + "/" + name;
    std::ofstream(path) << text;
    return path;
}

std::string error_of(const std::string& path) {
    try {
        read_mesh(path);
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::bad_input);
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST(MeshReader, HouseObjHasMaterialsPerFace) {
    TriangleMesh m = read_mesh(PENINK_SOURCE_DIR "/examples/models/house.obj");
    EXPECT_EQ(m.triangles.size(), m.material.size());
    std::vector<std::string> expected = {"brick_walls", "window", "door", "roof", "stone_chimney", "ground"};
    EXPECT_EQ(m.material_names, expected);
    std::map<std::string, int> count;
    for (auto id : m.material) count[m.material_names[id]]++;
    EXPECT_EQ(count["ground"], 2);     // one quad
    EXPECT_EQ(count["roof"], 4);       // two quads
    EXPECT_EQ(count["door"], 4);       // two wall cells
    EXPECT_EQ(count["stone_chimney"], 10);
    glm::vec3 lo, hi;
    ASSERT_TRUE(mesh_bounds(m, lo, hi));
    EXPECT_FLOAT_EQ(lo.y, 0.0f);
    EXPECT_FLOAT_EQ(hi.y, 7.6f);  // chimney top, y up
    mesh_y_up_to_z_up(m);
    ASSERT_TRUE(mesh_bounds(m, lo, hi));
    EXPECT_FLOAT_EQ(hi.z, 7.6f);
    EXPECT_FLOAT_EQ(lo.y, -12.0f);  // z = 12 -> y = -12
}

TEST(MeshReader, ScansUsemtlPerFaceLine) {
    auto mats = scan_obj_face_materials("v 0 0 0\nf 1 2 3\nusemtl  red brick \nf 1 2 3 4\n# f x\nusemtl\nf 3 2 1\n");
    EXPECT_EQ(mats, (std::vector<std::string>{"default", "red brick", "default"}));
}

TEST(MeshReader, FansPolygonsAndWeldsSplitVertices) {
    // A unit square as a quad plus a triangle on a duplicated edge (vertices 5, 6 = 2, 3).
    std::string path = temp_file("quad.obj",
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 0 0\nv 1 1 0\nv 2 0.5 0\n"
                                 "usemtl a\nf 1 2 3 4\nusemtl b\nf 5 7 6\n");
    TriangleMesh welded = read_mesh(path);
    EXPECT_EQ(welded.positions.size(), 5u);
    ASSERT_EQ(welded.triangles.size(), 3u);
    EXPECT_EQ(welded.triangles[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(welded.triangles[1], glm::uvec3(0, 2, 3));
    EXPECT_EQ(welded.triangles[2], glm::uvec3(1, 4, 2));
    EXPECT_EQ(welded.material, (std::vector<std::uint32_t>{0, 0, 1}));
    TriangleMesh raw = read_mesh(path, false);
    EXPECT_EQ(raw.positions.size(), 7u);
}

TEST(MeshReader, ReadsOffAndPly) {
    TriangleMesh w = read_mesh(PENINK_SOURCE_DIR "/examples/models/wuson.off");
    EXPECT_EQ(w.triangles.size(), 3732u);
    EXPECT_EQ(w.material_names, std::vector<std::string>{"default"});
    std::string ply = temp_file("tet.PLY",
                                "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                                "property float z\nelement face 4\nproperty list uchar int vertex_indices\n"
                                "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n");
    TriangleMesh t = read_mesh(ply);
    EXPECT_EQ(t.positions.size(), 4u);
    EXPECT_EQ(t.triangles.size(), 4u);
    EXPECT_EQ(t.source, ply);
}

TEST(MeshReader, ErrorsAreExact) {
    std::string dir = testing::TempDir();
    EXPECT_EQ(error_of(dir + "/missing.obj"), "penink: input: " + dir + "/missing.obj: no such file");
    std::string xyz = temp_file("points.xyz", "1 2 3\n");
    EXPECT_EQ(error_of(xyz), "penink: input: " + xyz +
                                 ": unsupported mesh format \".xyz\" (use .obj, .ply or .off)");
    std::string bad = temp_file("bad.off", "this is not an OFF file\n");
    EXPECT_EQ(error_of(bad), "penink: input: " + bad + ": not a mesh (OFF: line 1: expected the vertex and face counts)");
    std::string empty = temp_file("points.obj", "v 0 0 0\nv 1 0 0\n");
    EXPECT_EQ(error_of(empty), "penink: input: " + empty + ": mesh has no triangles");
}

TEST(MeshReader, CoordinatesBeyondRangeOrNotFiniteAreRefused) {
    const std::string tri = "f 1 2 3\n";
    std::string huge = temp_file("huge.obj", "v 0 0 0\nv 1e308 0 0\nv 0 1 0\n" + tri);
    EXPECT_EQ(error_of(huge), "penink: input: " + huge +
                                  ": vertex 2 has coordinate 1e+308, out of range (mesh coordinates must be finite and within +-1e9)");
    std::string f38 = temp_file("f38.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1e38 0\n3 0 1 2\n");
    EXPECT_EQ(error_of(f38), "penink: input: " + f38 +
                                 ": vertex 3 has coordinate 1e+38, out of range (mesh coordinates must be finite and within +-1e9)");
    std::string inf = temp_file("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 inf\n" + tri);
    EXPECT_EQ(error_of(inf).rfind("penink: input: " + inf + ": ", 0), 0u);  // CGAL stops at "inf": some refusal
    std::string ok = temp_file("ok.obj", "v 0 0 0\nv 1e9 0 0\nv 0 -1e9 0\n" + tri);
    EXPECT_EQ(error_of(ok), "no error");
}

TEST(MeshReader, PlyHeadersCheckedBeforeCgalReadsThem) {
    // a property before any element crashed CGAL's reader (found by fuzzing)
    std::string early = temp_file("early.ply", "ply\nformat ascii 1.0\nproperty float z\nelement vertex 1\nend_header\n0\n");
    EXPECT_EQ(error_of(early), "penink: input: " + early + ": not a mesh (PLY header: line 3: property before any element)");
    std::string many = temp_file("many.ply", "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\n"
                                             "end_header\n0\n");
    EXPECT_EQ(error_of(many), "penink: input: " + many +
                                  ": not a mesh (PLY header: declares 1000000000 elements, more than the 2 bytes after it hold)");
    std::string open = temp_file("open.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n");
    EXPECT_EQ(error_of(open), "penink: input: " + open + ": not a mesh (PLY header: no end_header)");
    std::string word = temp_file("word.ply", "ply\nformat ascii 1.0\nvertices 3\nend_header\n");
    EXPECT_EQ(error_of(word), "penink: input: " + word + ": not a mesh (PLY header: line 3: unknown keyword \"vertices\")");
}

TEST(MeshReader, OffReadHereWhateverFollowsTheCoordinates) {
    // CGAL's reader read past its arrays on a colour line shorter than COFF promises (fuzzing)
    std::string colours = temp_file("c.off", "COFF\n3 1 0\n0 0 0 255\n1 0 0 0 255 0 255\n0 1 0\n3 0 1 2 7 7 7\n");
    EXPECT_EQ(error_of(colours), "no error");
    std::string same_line = temp_file("s.off", "OFF 3 1 0 # counts here\n0 0 0\n1 0 0\n0 1 0\n\n3 0 1 2\n");
    EXPECT_EQ(read_mesh(same_line).triangles.size(), 1u);
    std::string bare = temp_file("b.off", "4 1\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
    EXPECT_EQ(read_mesh(bare).triangles.size(), 2u);
    std::string short_vertex = temp_file("v.off", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n");
    EXPECT_EQ(error_of(short_vertex), "penink: input: " + short_vertex + ": not a mesh (OFF: line 4: expected vertex x y z)");
    std::string binary = temp_file("bin.off", "OFF BINARY\n");
    EXPECT_EQ(error_of(binary), "penink: input: " + binary + ": not a mesh (OFF: binary files are not read)");
    std::string four = temp_file("4.off", "4OFF\n1 0 0\n0 0 0 0\n");
    EXPECT_EQ(error_of(four), "penink: input: " + four + ": not a mesh (OFF: \"4OFF\" files are not read)");
    std::string huge = temp_file("h.off", "OFF\n1000000000 1 0\n0 0 0\n");
    EXPECT_EQ(error_of(huge), "penink: input: " + huge +
                                  ": not a mesh (OFF: declares 1000000000 vertices and 1 faces, more than its 25 bytes hold)");
    std::string mixed = temp_file("m.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                                           "property int z\nend_header\n0 0 0\n");
    EXPECT_EQ(error_of(mixed), "penink: input: " + mixed +
                                   ": not a mesh (PLY header: vertex x, y and z must be float or double numbers (CGAL reads no other))");
}
