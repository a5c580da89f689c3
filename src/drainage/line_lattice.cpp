#include "drainage/line_lattice.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <tuple>

namespace penink {

namespace {

constexpr std::uint32_t zero_normal = normal_levels + 1;
constexpr int flow_shift = 23 - flow_bits;  // float32 mantissa bits dropped

// 2^e for |e| < 1023 (its bits: no call, exact)
double power_of_two(int e) { return std::bit_cast<double>(std::uint64_t(1023 + e) << 52); }
// The integer nearest x / 2^e (exact: a power of two's scaling), false beyond int32 or not finite.
bool steps(float x, int e, std::int32_t& q) {
    const double s = std::nearbyint(double(x) * power_of_two(-e));
    if (!(std::fabs(s) < 2147483648.0)) return false;
    q = std::int32_t(s);
    return true;
}
float of_steps(std::int32_t q, double step) { return float(double(q) * step); }  // exact before the rounding

// A component of [-1, 1] in normal_levels steps (nearest), and back.
std::uint32_t normal_step(double a) {
    return std::uint32_t(std::nearbyint(std::clamp((a + 1.0) * 0.5, 0.0, 1.0) * normal_levels));
}
double of_normal_step(std::uint32_t q) { return 2.0 * double(q) / normal_levels - 1.0; }

// The normal's code (zero_normal for a zero normal).
void normal_code(float nx, float ny, float nz, std::uint32_t& a, std::uint32_t& b) {
    const double l1 = std::fabs(double(nx)) + std::fabs(double(ny)) + std::fabs(double(nz));
    if (!(l1 > 0.0)) {
        a = zero_normal, b = 0;
        return;
    }
    const double u = nx / l1, v = ny / l1;
    a = normal_step(u + v), b = normal_step(u - v);
}

}  // namespace

LineLattice line_lattice(double cell) {
    LineLattice out;
    out.plan_exp = int(std::floor(std::log2(cell / 64.0)));
    out.z_exp = out.plan_exp - 1;
    return out;
}

void lattice_vertices(const VertexCode* codes, std::size_t n, const LineLattice& lattice, DrapedVertex* out) {
    const double plan = power_of_two(lattice.plan_exp), zs = power_of_two(lattice.z_exp);
    for (std::size_t i = 0; i < n; ++i) {
        const VertexCode& c = codes[i];
        DrapedVertex& v = out[i];
        v.x = of_steps(c.x, plan), v.y = of_steps(c.y, plan), v.z = of_steps(c.z, zs);
        v.nx = v.ny = v.nz = 0.0f;
        if (c.a <= normal_levels && c.b <= normal_levels) {
            const double a = of_normal_step(c.a), b = of_normal_step(c.b);
            const double u = 0.5 * (a + b), w = 0.5 * (a - b), h = 1.0 - std::fabs(u) - std::fabs(w);
            const double inv = 1.0 / std::sqrt(u * u + w * w + h * h);
            v.nx = float(u * inv), v.ny = float(w * inv), v.nz = float(h * inv);
        }
        v.flow = std::bit_cast<float>(c.flow << flow_shift);
    }
}

DrapedVertex lattice_vertex(const VertexCode& c, const LineLattice& lattice) {
    DrapedVertex v;
    lattice_vertices(&c, 1, lattice, &v);
    return v;
}

bool vertex_code(const DrapedVertex& v, const LineLattice& lattice, VertexCode& c) {
    if (!steps(v.x, lattice.plan_exp, c.x) || !steps(v.y, lattice.plan_exp, c.y) || !steps(v.z, lattice.z_exp, c.z))
        return false;
    normal_code(v.nx, v.ny, v.nz, c.a, c.b);
    c.flow = std::bit_cast<std::uint32_t>(v.flow) >> flow_shift;
    const DrapedVertex back = lattice_vertex(c, lattice);
    return std::memcmp(&back, &v, sizeof v) == 0;
}

DrapedVertex snapped_vertex(const DrapedVertex& v, const LineLattice& lattice, glm::vec2 lo, glm::vec2 hi) {
    VertexCode c;
    if (!steps(v.x, lattice.plan_exp, c.x) || !steps(v.y, lattice.plan_exp, c.y) || !steps(v.z, lattice.z_exp, c.z))
        return v;
    const double plan = power_of_two(lattice.plan_exp);
    for (auto [q, l, h] : {std::tuple(&c.x, lo.x, hi.x), std::tuple(&c.y, lo.y, hi.y)}) {
        if (of_steps(*q, plan) > h) --*q;
        else if (of_steps(*q, plan) < l) ++*q;
    }
    normal_code(v.nx, v.ny, v.nz, c.a, c.b);
    // the flow's bits rounded half up to flow_bits of mantissa (monotone in the float's bits; an
    // infinity or NaN cut, as it is kept)
    const std::uint32_t f = std::bit_cast<std::uint32_t>(v.flow);
    c.flow = (std::isfinite(v.flow) ? f + (1u << (flow_shift - 1)) : f) >> flow_shift;
    return lattice_vertex(c, lattice);
}

}  // namespace penink
