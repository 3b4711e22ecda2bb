// The manifold walk against closed-form and brute-force solutions, and the generalised
// geometry term |do_b/dx_c| against finite differences of the light-point map.
#include <gtest/gtest.h>

#include "manifold/chain_fixture.h"
#include "manifold/generalized_geometry.h"
#include "manifold/manifold_walk.h"

using namespace snell;
using namespace snell::test;

namespace {

WalkSettings precise() {
    WalkSettings s;
    s.max_iterations = 60;
    s.threshold = 1e-12;
    return s;
}

// Bisection for the root of a monotone function on [lo, hi].
template <typename F>
double bisect(F f, double lo, double hi) {
    const double flo = f(lo);
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        if ((f(mid) > 0) == (flo > 0))
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace

TEST(ManifoldWalk, FlatInterfaceConvergesToSnellsLaw) {
    // Interface z = 0 (normal +z, outside air), water below with eta 1.33.
    TriangleMesh plane(make_rectangle(Transform::scale({10, 10, 1})), true, false, "plane");
    const double eta = 1.33;
    const Vec3 xb(0.2, -0.1, -1.0), xc(2.0, 0.9, 1.5);
    // Seed: where the straight segment crosses the plane.
    const double ts = 1.0 / 2.5;
    std::vector<ManifoldVertex> chain = {vertex_on(plane, xb + (xc - xb) * ts, eta)};
    const WalkResult r = manifold_walk(nullptr, xb, chain, endpoint(xc, Vec3(0, 0, -1)), precise());
    ASSERT_EQ(r.outcome, WalkOutcome::Converged) << "error " << r.error;

    // Closed form: the point p on the line between the projections of xb and xc where
    // eta sin(theta_water) = sin(theta_air) (Snell), found by bisection.
    const Vec3 a(xb.x, xb.y, 0), b(xc.x, xc.y, 0);
    const double D = length(b - a), hb = -xb.z, hc = xc.z;
    const double s = bisect(
        [&](double x) {
            const double sin_w = x / std::sqrt(x * x + hb * hb), sin_a = (D - x) / std::sqrt(sqr(D - x) + hc * hc);
            return eta * sin_w - sin_a;
        },
        0.0, D);
    const Vec3 expected = a + (b - a) * (s / D);
    EXPECT_NEAR(length(chain[0].p - expected), 0.0, 1e-9);
}

TEST(ManifoldWalk, SlabOfTwoInterfacesConvergesToClosedForm) {
    // Glass slab between z = 0 and z = 0.5 (eta 1.5), normals pointing out of the slab.
    TriangleMesh bottom(make_rectangle(Transform::scale({10, 10, 1})), true, true, "bottom");  // normal -z
    TriangleMesh top(make_rectangle(Transform::translate({0, 0, 0.5}) * Transform::scale({10, 10, 1})), true, false,
                     "top");
    const double eta = 1.5, t1 = 1.0, t2 = 0.5, t3 = 1.2, D = 1.5;
    const Vec3 xb(0, 0, -t1), xc(D, 0, t2 + t3);
    // Seed: the straight segment's crossings (paper Sec. 3.1).
    const Vec3 dir = xc - xb;
    std::vector<ManifoldVertex> chain = {vertex_on(bottom, xb + dir * (t1 / dir.z), eta),
                                         vertex_on(top, xb + dir * ((t1 + t2) / dir.z), eta)};
    const WalkResult r = manifold_walk(nullptr, xb, chain, endpoint(xc, Vec3(0, 0, -1)), precise());
    ASSERT_EQ(r.outcome, WalkOutcome::Converged) << "error " << r.error;
    // Closed form: sin(theta_air) = eta sin(theta_glass), horizontal distances add up to D.
    const double th = bisect(
        [&](double theta) {
            const double sg = std::sin(theta) / eta;
            return t1 * std::tan(theta) + t2 * sg / std::sqrt(1 - sg * sg) + t3 * std::tan(theta) - D;
        },
        0.0, 1.5);
    EXPECT_NEAR(chain[0].p.x, t1 * std::tan(th), 1e-9);
    EXPECT_NEAR(chain[1].p.x, D - t3 * std::tan(th), 1e-9);
    EXPECT_NEAR(chain[0].p.y, 0.0, 1e-9);
}

TEST(ManifoldWalk, SphereMatchesBruteForceSearch) {
    // Droplet: receiver point under a water sphere, light above and to the side.
    Sphere s(Vec3(0, 0, 0.35), 1.0);
    const double eta = 1.33;
    const Vec3 xb(0.25, 0.1, 0.0), xc(-2.5, 1.5, 7.0);
    std::vector<ManifoldVertex> chain = {vertex_on(s, xb + normalize(xc - xb) * 1.2, eta)};
    const WalkResult r = manifold_walk(nullptr, xb, chain, endpoint(xc, xb - xc), precise());
    ASSERT_EQ(r.outcome, WalkOutcome::Converged) << "error " << r.error;

    // Brute force: scan the upper hemisphere for the smallest constraint violation, refine.
    double best = kInfinity;
    Vec3 best_p;
    double th0 = 0, ph0 = 0, step = 0.02;
    for (int level = 0; level < 6; ++level) {
        const double lo_th = level ? th0 - 10 * step : 0.0, hi_th = level ? th0 + 10 * step : kPi / 2;
        const double lo_ph = level ? ph0 - 10 * step : -kPi, hi_ph = level ? ph0 + 10 * step : kPi;
        for (double th = lo_th; th <= hi_th; th += step)
            for (double ph = lo_ph; ph <= hi_ph; ph += step) {
                const Vec3 p =
                    s.center() + Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
                const ManifoldVertex v = vertex_on(s, p, eta);
                const Vec2 c = half_vector_constraint_value(xb, v, xc);
                const double e = c.x * c.x + c.y * c.y;
                if (e < best) {
                    best = e;
                    best_p = v.p;
                    th0 = th;
                    ph0 = ph;
                }
            }
        step *= 0.1;
    }
    EXPECT_LT(best, 1e-12);
    EXPECT_NEAR(length(chain[0].p - best_p), 0.0, 1e-5);
}

TEST(ManifoldWalk, SphereInSphereConverges) {
    // Four refractions: into water (1.33), into a glass core (1.5/1.33), out of both.
    Sphere outer(Vec3(0, 0, 0), 1.0);
    Sphere inner(Vec3(0, 0, 0.05), 0.45);
    const double e_out = 1.33, e_in = 1.5 / 1.33;
    const Vec3 xb(0.3, 0.1, -2.0), xc(-0.6, 0.4, 4.0);
    std::vector<ManifoldVertex> chain = {
        vertex_on(outer, Vec3(0.2, 0.1, -1), e_out), vertex_on(inner, Vec3(0.1, 0.1, -0.4), e_in),
        vertex_on(inner, Vec3(0.0, 0.1, 0.5), e_in), vertex_on(outer, Vec3(-0.1, 0.1, 1), e_out)};
    WalkSettings st = precise();
    const WalkResult r = manifold_walk(nullptr, xb, chain, endpoint(xc, Vec3(0, 0, -1)), st);
    ASSERT_EQ(r.outcome, WalkOutcome::Converged) << "error " << r.error;
    // Snell's law holds at each vertex: eta_i sin(theta_i) = eta_o sin(theta_o) with the
    // tangential components of the two unit directions opposite.
    std::vector<Vec3> pts = {xb};
    for (auto& v : chain) pts.push_back(v.p);
    pts.push_back(xc);
    for (size_t i = 0; i < chain.size(); ++i) {
        const Vec3 wi = normalize(pts[i] - pts[i + 1]), wo = normalize(pts[i + 2] - pts[i + 1]);
        const Vec3 n = chain[i].ng;
        const double ei = dot(wi, n) > 0 ? 1.0 : chain[i].eta, eo = dot(wo, n) > 0 ? 1.0 : chain[i].eta;
        EXPECT_LT(dot(wi, n) * dot(wo, n), 0.0) << "vertex " << i << " must transmit";
        const Vec3 ti = (wi - n * dot(wi, n)) * ei, to = (wo - n * dot(wo, n)) * eo;
        EXPECT_NEAR(length(ti + to), 0.0, 1e-9) << "vertex " << i;
    }
}

TEST(ManifoldWalk, GeneralizedGeometryTermMatchesFiniteDifferences) {
    Sphere s(Vec3(0, 0, 0), 1.0);
    const Vec3 xb(0.3, -0.2, -2.5);
    const Vec3 xc(0.5, 0.4, 3);
    const TangentBasis basis = endpoint(xc, Vec3(0.1, 0.2, -1));
    std::vector<ManifoldVertex> chain = {vertex_on(s, Vec3(0.1, 0.05, -1), 1.33, Vec2(0.05, -0.02)),
                                         vertex_on(s, Vec3(0.2, -0.1, 1), 1.33, Vec2(-0.03, 0.04))};
    ASSERT_EQ(manifold_walk(nullptr, xb, chain, basis, precise()).outcome, WalkOutcome::Converged);
    const ChainJacobians jac = chain_jacobians(xb, chain, basis);
    ASSERT_TRUE(jac.valid);

    const Vec3 o = normalize(chain[0].p - xb);
    const Frame f = Frame::from_normal(o);
    const double h = 1e-5;
    Vec2 col[2];
    for (int axis = 0; axis < 2; ++axis) {
        Vec3 dir[2];
        for (int sgn = 0; sgn < 2; ++sgn) {
            const Vec3 e = (axis == 0 ? basis.dp_ds : basis.dp_dt) * (sgn ? -h : h);
            std::vector<ManifoldVertex> c = chain;
            const TangentBasis moved{xc + e, basis.dp_ds, basis.dp_dt};
            EXPECT_EQ(manifold_walk(nullptr, xb, c, moved, precise()).outcome, WalkOutcome::Converged);
            dir[sgn] = normalize(c[0].p - xb);
        }
        const Vec3 d = (dir[0] - dir[1]) / (2 * h);
        col[axis] = Vec2(dot(d, f.s), dot(d, f.t));
    }
    const double fd = std::abs(Mat2::from_columns(col[0], col[1]).det());
    EXPECT_NEAR(jac.do_b_dx_c, fd, 1e-4 * fd);
}

TEST(ManifoldWalk, MirrorReflectionGivesTheGeometryTermOfTheMirrorImage) {
    // One specular reflection off the plane z = 0: |do_b/dx_c| = cos(theta_c) / d^2 with d the
    // distance from x_b to the mirror image of x_c (closed form).
    TriangleMesh plane(make_rectangle(Transform::scale({10, 10, 1})), true, false, "mirror");
    const Vec3 xb(0.2, -0.1, 1.0), xc(2.0, 0.9, 1.5), nc = normalize(Vec3(-0.3, -0.2, -1));
    std::vector<ManifoldVertex> chain = {vertex_on(plane, (xb + xc) * 0.5, 1.0)};
    const TangentBasis basis = endpoint(xc, nc);
    ASSERT_EQ(manifold_walk(nullptr, xb, chain, basis, precise()).outcome, WalkOutcome::Converged);
    const ChainJacobians jac = chain_jacobians(xb, chain, basis);
    const Vec3 image(xc.x, xc.y, -xc.z);
    const double d = length(image - xb);
    const double cos_c = std::abs(dot(nc, normalize(xc - chain[0].p)));
    const double expected = cos_c / (d * d);
    EXPECT_NEAR(jac.do_b_dx_c, expected, 1e-9 * expected);
}

// min_step ends a walk that can only be rejected: the solution lies far beyond the edge of a
// small interface, so once the walk reaches the edge no step lowers the error and the step
// size halves until it falls below min_step.
TEST(ManifoldWalk, StalledWalkEndsEarly) {
    TriangleMesh plane(make_rectangle(Transform::scale({0.5, 0.5, 1})), true, false, "plane");
    const Vec3 xb(0.0, 0.0, -1.0), xc(40.0, 0.0, 0.2);
    const auto walk = [&](double min_step) {
        std::vector<ManifoldVertex> chain = {vertex_on(plane, Vec3(0.1, 0.0, 0.0), 1.33)};
        WalkSettings s = precise();
        s.min_step = min_step;
        return manifold_walk(nullptr, xb, chain, endpoint(xc, Vec3(0, 0, -1)), s);
    };
    const WalkResult early = walk(0.1), late = walk(1e-4);
    EXPECT_EQ(early.outcome, WalkOutcome::Stalled);
    EXPECT_EQ(late.outcome, WalkOutcome::Stalled);
    EXPECT_LT(early.iterations + 5, late.iterations);
}

// The progress test: where no solution exists the error settles on a plateau; with a window of 3
// iterations and ratio 0.7 the walk ends as Stalled long before max_iterations, while a walk to
// an existing solution (whose error falls by large factors) converges as without the test.
TEST(ManifoldWalk, ProgressTestEndsWalksOnAPlateau) {
    TriangleMesh plane(make_rectangle(Transform::scale({0.5, 0.5, 1})), true, false, "plane");
    const Vec3 xb(0.0, 0.0, -1.0);
    const auto walk = [&](const Vec3& xc, int window) {
        std::vector<ManifoldVertex> chain = {vertex_on(plane, Vec3(0.1, 0.0, 0.0), 1.33)};
        WalkSettings s = precise();
        s.max_iterations = 60;
        s.stall_window = window;
        s.stall_ratio = 0.7;
        return manifold_walk(nullptr, xb, chain, endpoint(xc, Vec3(0, 0, -1)), s);
    };
    const Vec3 unreachable(40.0, 0.0, 0.2), reachable(0.3, 0.2, 1.5);
    const WalkResult tested = walk(unreachable, 3), untested = walk(unreachable, 0);
    EXPECT_NE(tested.outcome, WalkOutcome::Converged);
    EXPECT_NE(untested.outcome, WalkOutcome::Converged);
    EXPECT_EQ(tested.outcome, WalkOutcome::Stalled);
    EXPECT_LT(tested.iterations, untested.iterations);
    const WalkResult ok = walk(reachable, 3), ok_untested = walk(reachable, 0);
    EXPECT_EQ(ok.outcome, WalkOutcome::Converged);
    EXPECT_EQ(ok.iterations, ok_untested.iterations);
}
