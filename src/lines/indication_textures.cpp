#include "lines/indication_textures.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <glm/geometric.hpp>

#include "core/error.hpp"
#include "lines/random_bits.hpp"

namespace penink {
namespace {

double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
double lerp(double a, double b, double t) { return a + t * (b - a); }

double grad3(int h, double x, double y, double z) {
    h &= 15;
    double u = h < 8 ? x : y, v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
    return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

}  // namespace

PerlinNoise make_perlin(std::uint64_t seed) {
    PerlinNoise n;
    std::array<std::uint8_t, 256> p;
    for (int i = 0; i < 256; ++i) p[i] = std::uint8_t(i);
    for (int i = 255; i > 0; --i) std::swap(p[i], p[random_bits(seed, 0x9e71, i) % std::uint64_t(i + 1)]);
    for (int i = 0; i < 512; ++i) n.perm[i] = p[i & 255];
    return n;
}

double perlin3(const PerlinNoise& n, double x, double y, double z) {
    const auto& P = n.perm;
    int X = int(std::floor(x)) & 255, Y = int(std::floor(y)) & 255, Z = int(std::floor(z)) & 255;
    x -= std::floor(x), y -= std::floor(y), z -= std::floor(z);
    double u = fade(x), v = fade(y), w = fade(z);
    int A = P[X] + Y, AA = P[A] + Z, AB = P[A + 1] + Z;
    int B = P[X + 1] + Y, BA = P[B] + Z, BB = P[B + 1] + Z;
    return lerp(lerp(lerp(grad3(P[AA], x, y, z), grad3(P[BA], x - 1, y, z), u),
                     lerp(grad3(P[AB], x, y - 1, z), grad3(P[BB], x - 1, y - 1, z), u), v),
                lerp(lerp(grad3(P[AA + 1], x, y, z - 1), grad3(P[BA + 1], x - 1, y, z - 1), u),
                     lerp(grad3(P[AB + 1], x, y - 1, z - 1), grad3(P[BB + 1], x - 1, y - 1, z - 1), u),
                     v),
                w);
}

namespace {

std::vector<glm::vec2> parse_stroke(const std::string& line, const std::string& file) {
    std::istringstream in(line);
    std::vector<float> v;
    std::string tok;
    while (in >> tok) {
        char* end = nullptr;
        float x = std::strtof(tok.c_str(), &end);
        if (end != tok.c_str() + tok.size()) throw Error("textures", file, "bad number \"" + tok + "\"");
        if (x < 0.0f || x > 1.0f) throw Error("textures", file, "coordinate outside the unit square");
        v.push_back(x);
    }
    if (v.size() % 2) throw Error("textures", file, "odd number of coordinates");
    std::vector<glm::vec2> pts;
    for (std::size_t i = 0; i + 1 < v.size(); i += 2) pts.emplace_back(v[i], v[i + 1]);
    return pts;
}

std::vector<StrokeCluster> parse_clusters(const std::string& file) {
    std::ifstream in(file);
    std::vector<StrokeCluster> out;
    std::string line;
    while (std::getline(in, line)) {
        std::size_t first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        if (line.compare(first, 7, "variant") == 0) {
            out.emplace_back();
            continue;
        }
        if (out.empty()) out.emplace_back();
        auto pts = parse_stroke(line, file);
        if (pts.size() >= 2) out.back().push_back(std::move(pts));
    }
    out.erase(std::remove_if(out.begin(), out.end(), [](const auto& c) { return c.empty(); }), out.end());
    if (out.empty()) throw Error("textures", file, "no cluster");
    return out;
}

}  // namespace

TextureLibrary load_texture_library(const std::string& dir) {
    namespace fs = std::filesystem;
    std::vector<fs::path> files;
    if (fs::is_directory(dir))
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().extension() == ".txt") files.push_back(e.path());
    if (files.empty()) throw Error("textures", dir, "no texture library here");
    std::sort(files.begin(), files.end());
    TextureLibrary lib;
    for (const auto& f : files) lib.textures[f.stem().string()] = parse_clusters(f.string());
    return lib;
}

std::string default_texture_for_material(const std::string& material) {
    std::string m = material;
    std::transform(m.begin(), m.end(), m.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    auto has = [&](const char* k) { return m.find(k) != std::string::npos; };
    if (has("brick") || has("wall")) return "bricks";
    if (has("roof") || has("shingle") || has("tile")) return "shingles";
    if (has("stone") || has("rock")) return "stone";
    if (has("grass") || has("ground") || has("lawn")) return "grass";
    if (has("hatch")) return "hatching";
    return "";
}

namespace {

// A planar face group in its own 2D frame: u along `t`, v along `b` (world units).
struct Group {
    std::vector<int> faces;
    glm::vec3 n{0.0f}, t{0.0f}, b{0.0f};
    glm::vec2 lo{1e30f}, hi{-1e30f};
    std::vector<std::array<glm::vec2, 2>> feature_edges;  // 2D, for the "near edge" term
    std::uint32_t material = 0;
};

glm::vec2 to_2d(const Group& g, const glm::vec3& p) { return {glm::dot(p, g.t), glm::dot(p, g.b)}; }

// Stable tangent basis: t horizontal (perpendicular to up and n), b = n x t; for a face
// facing up or down, t is the world x axis projected on the plane.
void frame(Group& g, const glm::vec3& up) {
    glm::vec3 t = glm::cross(up, g.n);
    if (glm::length(t) < 0.2f) t = glm::vec3(1, 0, 0) - g.n * g.n.x;
    g.t = glm::normalize(t);
    g.b = glm::cross(g.n, g.t);
}

std::vector<Group> build_groups(const TriangleMesh& m, const std::vector<MeshEdge>& edges,
                                const FaceGroups& fg, const glm::vec3& up) {
    std::vector<Group> gs(fg.count);
    for (std::size_t f = 0; f < m.triangles.size(); ++f) {
        Group& g = gs[fg.group[f]];
        g.faces.push_back(int(f));
        g.material = m.material[f];
        const glm::uvec3& t = m.triangles[f];
        g.n += glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    }
    for (Group& g : gs) {
        g.n = glm::length(g.n) > 0.0f ? glm::normalize(g.n) : glm::vec3(0, 0, 1);
        frame(g, up);
        for (int f : g.faces)
            for (int k = 0; k < 3; ++k) {
                glm::vec2 q = to_2d(g, m.positions[m.triangles[f][k]]);
                g.lo = glm::min(g.lo, q), g.hi = glm::max(g.hi, q);
            }
    }
    for (const MeshEdge& e : edges) {
        if (e.kind == EdgeKind::none) continue;
        for (int f : {e.face0, e.face1}) {
            if (f < 0) continue;
            Group& g = gs[fg.group[f]];
            g.feature_edges.push_back({to_2d(g, m.positions[e.a]), to_2d(g, m.positions[e.b])});
        }
    }
    return gs;
}

float distance_to_segment(const glm::vec2& p, const glm::vec2& a, const glm::vec2& b) {
    glm::vec2 d = b - a;
    float len2 = glm::dot(d, d);
    float t = len2 > 0.0f ? std::clamp(glm::dot(p - a, d) / len2, 0.0f, 1.0f) : 0.0f;
    return glm::length(p - (a + t * d));
}

float cross2(const glm::vec2& a, const glm::vec2& b) { return a.x * b.y - a.y * b.x; }

// Parameter range [t0, t1] of segment a->b inside triangle q (Cyrus-Beck); false when outside.
bool clip_to_triangle(const glm::vec2& a, const glm::vec2& b, const glm::vec2 q[3], float& t0, float& t1) {
    float s = cross2(q[1] - q[0], q[2] - q[0]) >= 0.0f ? 1.0f : -1.0f;
    t0 = 0.0f, t1 = 1.0f;
    for (int i = 0; i < 3; ++i) {
        const glm::vec2 &e0 = q[i], &e1 = q[(i + 1) % 3];
        float fa = s * cross2(e1 - e0, a - e0), fb = s * cross2(e1 - e0, b - e0);
        if (fa < 0.0f && fb < 0.0f) return false;
        if (fa < 0.0f) t0 = std::max(t0, fa / (fa - fb));
        if (fb < 0.0f) t1 = std::min(t1, fa / (fa - fb));
    }
    return t1 - t0 > 1e-6f;
}

// World point of 2D point p inside face f of group g (barycentric lift onto the triangle).
glm::vec3 lift(const TriangleMesh& m, const Group& g, int f, const glm::vec2& p) {
    const glm::uvec3& t = m.triangles[f];
    glm::vec2 q0 = to_2d(g, m.positions[t.x]), q1 = to_2d(g, m.positions[t.y]), q2 = to_2d(g, m.positions[t.z]);
    float area = cross2(q1 - q0, q2 - q0);
    float b1 = cross2(p - q0, q2 - q0) / area, b2 = cross2(q1 - q0, p - q0) / area;
    return m.positions[t.x] + b1 * (m.positions[t.y] - m.positions[t.x]) +
           b2 * (m.positions[t.z] - m.positions[t.x]);
}

struct Piece {
    float t0, t1;
    int face;
};

// Clips a 2D stroke to the group's faces; appends world polylines to out.
void clip_stroke(const TriangleMesh& m, const Group& g, const std::vector<glm::vec2>& stroke,
                 ObjectPolyline proto, std::vector<ObjectPolyline>& out) {
    ObjectPolyline cur = proto;
    for (std::size_t i = 1; i < stroke.size(); ++i) {
        const glm::vec2 a = stroke[i - 1], b = stroke[i];
        glm::vec2 slo = glm::min(a, b), shi = glm::max(a, b);
        std::vector<Piece> pieces;
        for (int f : g.faces) {
            const glm::uvec3& t = m.triangles[f];
            glm::vec2 q[3] = {to_2d(g, m.positions[t.x]), to_2d(g, m.positions[t.y]), to_2d(g, m.positions[t.z])};
            glm::vec2 qlo = glm::min(q[0], glm::min(q[1], q[2])), qhi = glm::max(q[0], glm::max(q[1], q[2]));
            if (qhi.x < slo.x || qhi.y < slo.y || qlo.x > shi.x || qlo.y > shi.y) continue;
            float t0, t1;
            if (clip_to_triangle(a, b, q, t0, t1)) pieces.push_back({t0, t1, f});
        }
        std::sort(pieces.begin(), pieces.end(), [](const Piece& x, const Piece& y) { return x.t0 < y.t0; });
        float reached = cur.points.empty() ? -1.0f : 0.0f;  // where the open polyline ends on a->b
        for (const Piece& p : pieces) {
            if (p.t1 <= reached + 1e-6f) continue;
            if (p.t0 > reached + 1e-5f) {  // gap: close the open polyline
                if (cur.points.size() >= 2) out.push_back(cur);
                cur = proto;
                cur.points.push_back(lift(m, g, p.face, a + p.t0 * (b - a)));
            }
            cur.points.push_back(lift(m, g, p.face, a + p.t1 * (b - a)));
            reached = p.t1;
        }
        if (reached < 1.0f - 1e-5f) {
            if (cur.points.size() >= 2) out.push_back(cur);
            cur = proto;
        }
    }
    if (cur.points.size() >= 2) out.push_back(cur);
}

double unit(std::uint64_t seed, std::uint64_t id, std::uint64_t k) { return random_unit(seed, id, k); }

// Cluster strokes mapped to cell (i, j) of size s with sketchy jitter and overshoot.
std::vector<std::vector<glm::vec2>> place_cluster(const StrokeCluster& c, int i, int j, float s,
                                                  float confidence, std::uint64_t seed, std::uint64_t id) {
    const float sk = std::clamp(1.0f - confidence, 0.0f, 1.0f);
    std::vector<std::vector<glm::vec2>> out;
    std::uint64_t k = 0;
    for (const auto& stroke : c) {
        std::vector<glm::vec2> pts;
        for (const glm::vec2& p : stroke) {
            glm::vec2 jit(unit(seed, id, k) * 2 - 1, unit(seed, id, k + 1) * 2 - 1);
            k += 2;
            pts.push_back((glm::vec2(i, j) + p + 0.03f * sk * jit) * s);
        }
        float over = 0.12f * sk * float(unit(seed, id, k++));
        glm::vec2 d0 = pts[0] - pts[1], d1 = pts.back() - pts[pts.size() - 2];
        if (glm::length(d0) > 0.0f) pts.front() += over * s * glm::normalize(d0);
        if (glm::length(d1) > 0.0f) pts.back() += over * s * glm::normalize(d1);
        out.push_back(std::move(pts));
    }
    return out;
}

void texture_group(const TriangleMesh& m, const Group& g, int gi, const std::vector<StrokeCluster>& clusters,
                   const TextureStyle& st, const TextureOptions& o, const PerlinNoise& noise,
                   std::vector<ObjectPolyline>& out) {
    const float s = st.scale;
    const int i0 = int(std::floor(g.lo.x / s)), i1 = int(std::floor(g.hi.x / s));
    const int j0 = int(std::floor(g.lo.y / s)), j1 = int(std::floor(g.hi.y / s));
    const float offset = glm::dot(m.positions[m.triangles[g.faces[0]].x], g.n);
    ObjectPolyline proto;
    proto.kind = "texture";
    proto.material = m.material_names.at(g.material);
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
            glm::vec2 c((i + 0.5f) * s, (j + 0.5f) * s);
            glm::vec3 w = offset * g.n + c.x * g.t + c.y * g.b;
            float near = 1e30f;
            for (const auto& e : g.feature_edges) near = std::min(near, distance_to_segment(c, e[0], e[1]));
            float value = 0.5f * float(perlin3(noise, w.x / o.noise_scale, w.y / o.noise_scale,
                                               w.z / o.noise_scale) + 1.0) +
                          o.edge_weight * std::max(0.0f, 1.0f - near / o.edge_band);
            if (value <= o.threshold) continue;
            std::uint64_t id = random_bits(std::uint64_t(gi), std::uint64_t(i) * 0x10001, std::uint64_t(j));
            const auto& cl = clusters[random_bits(o.seed, id, 0xC1) % clusters.size()];
            for (const auto& stroke : place_cluster(cl, i, j, s, st.confidence, o.seed, id))
                clip_stroke(m, g, stroke, proto, out);
        }
}

}  // namespace

std::vector<ObjectPolyline> indication_textures(const TriangleMesh& mesh, const TextureLibrary& lib,
                                                const TextureOptions& options) {
    std::vector<MeshEdge> edges = classify_edges(mesh, options.features);
    FaceGroups fg = planar_face_groups(mesh, edges, options.planar_angle);
    std::vector<Group> groups = build_groups(mesh, edges, fg, options.up);
    PerlinNoise noise = make_perlin(options.seed);
    std::vector<ObjectPolyline> out;
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
        const Group& g = groups[gi];
        auto st = options.materials.find(mesh.material_names.at(g.material));
        if (st == options.materials.end() || st->second.scale <= 0.0f) continue;
        auto tex = lib.textures.find(st->second.texture);
        if (tex == lib.textures.end()) continue;
        texture_group(mesh, g, int(gi), tex->second, st->second, options, noise, out);
    }
    return out;
}

}  // namespace penink
