// same_solution: the test of Alg. 2 lines 5-7 (and later the de-duplication of solutions)
// decides by lengths relative to the chain's own segments, so it does not depend on the scene's
// scale, and it tells apart vertices on different shapes.
#include <gtest/gtest.h>

#include "manifold/chain_fixture.h"
#include "manifold/solution_set.h"

using namespace snell;
using namespace snell::test;

namespace {

// Two one-vertex chains on a sphere of radius r: the second moved along the surface by
// `offset` times the distance from x_b. Returns same_solution's verdict.
bool same_at_scale(double r, double offset) {
    const Sphere sphere(Vec3(0, 0, 0), r);
    const Vec3 xb(0, 0, -3 * r), xc(0.2 * r, 0, 4 * r);
    const Vec3 p = Vec3(0.1, 0.0, -1.0) * r;
    const std::vector<ManifoldVertex> a = {vertex_on(sphere, p, 1.33)};
    const double seg = length(a[0].p - xb);
    const std::vector<ManifoldVertex> b = {vertex_on(sphere, p + Vec3(0, 1, 0) * (offset * seg), 1.33)};
    return same_solution(xb, a, b, xc);
}

}  // namespace

TEST(SameSolution, IsScaleFree) {
    for (double r : {1e-3, 1.0, 1e3}) {
        EXPECT_TRUE(same_at_scale(r, 0.0)) << "r = " << r;
        EXPECT_TRUE(same_at_scale(r, 1e-7)) << "r = " << r;
        EXPECT_FALSE(same_at_scale(r, 1e-3)) << "r = " << r;
    }
}

TEST(SameSolution, DifferentShapesOrLengthsDiffer) {
    const Sphere s1(Vec3(0, 0, 0), 1.0), s2(Vec3(0, 0, 0), 1.0);
    const Vec3 xb(0, 0, -3), xc(0, 0, 4), p(0.1, 0, -1);
    const std::vector<ManifoldVertex> a = {vertex_on(s1, p, 1.33)}, b = {vertex_on(s2, p, 1.33)};
    EXPECT_FALSE(same_solution(xb, a, b, xc));  // same point, another shape
    const std::vector<ManifoldVertex> two = {vertex_on(s1, p, 1.33), vertex_on(s1, Vec3(0, 0, 1), 1.33)};
    EXPECT_FALSE(same_solution(xb, a, two, xc));
}
