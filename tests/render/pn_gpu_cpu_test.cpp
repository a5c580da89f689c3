// The GPU's PN maths (common.glsl, used by the tessellation stages) agrees with the CPU reference
// (src/surface/pn_triangle.hpp) on random patches: positions within 1e-5 of the patch size,
// normals within 1e-5. Both are float; differences come only from operation order (FMA).
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "support/gl_test_context.hpp"
#include "support/pn_eval.hpp"
#include "surface/pn_triangle.hpp"

using namespace penink;

TEST(PnGpuCpu, RandomPatchesAgree) {
    std::mt19937_64 rng(7);
    auto unit = [&] { return double(rng() >> 11) * (1.0 / 9007199254740992.0); };
    std::vector<PnQuery> queries;
    for (int i = 0; i < 500; ++i) {
        PnQuery q;
        for (int k = 0; k < 3; ++k) {
            q.p[k] = glm::vec3(unit() * 100, unit() * 100, unit() * 30);
            q.n[k] = glm::normalize(glm::vec3(unit() - 0.5, unit() - 0.5, 0.5 + unit()));
        }
        const float u = float(unit()), v = float(unit()) * (1.0f - u);
        q.bary = {1.0f - u - v, u, v};
        queries.push_back(q);
    }
    const std::vector<PnSample> gpu = evaluate_pn_on_gpu(test::test_context().gl(), queries);
    ASSERT_EQ(gpu.size(), queries.size());
    double max_pos = 0, max_nrm = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
        const PnQuery& q = queries[i];
        const PnPatch patch = pn_patch(q.p[0], q.p[1], q.p[2], q.n[0], q.n[1], q.n[2]);
        max_pos = std::max(max_pos, double(glm::length(gpu[i].position - pn_position(patch, q.bary))));
        max_nrm = std::max(max_nrm, double(glm::length(gpu[i].normal - pn_normal(patch, q.bary))));
    }
    EXPECT_LT(max_pos, 1e-3);  // 1e-5 of the ~100 m patch size
    EXPECT_LT(max_nrm, 1e-5);
}
