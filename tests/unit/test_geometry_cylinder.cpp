#include <gtest/gtest.h>

#include "core/rng.h"
#include "core/warp.h"
#include "geometry/cylinder.h"
#include "scene/scene.h"
#include "test_geometry_util.h"

using namespace snell;
using snell::test::next_2d;

namespace {

const Vec3 kP0(0.3, -0.2, 0.5), kP1(1.1, 0.9, -0.4);
constexpr double kR = 0.6;

SurfaceInteraction at(const Cylinder& c, double u, double v) {
    SurfaceInteraction si;
    c.fill_interaction(2 * kPi * u, v * length(kP1 - kP0), &si);
    return si;
}

// Distance of p from the segment p0 p1's line, and its axial coordinate.
std::pair<double, double> radial_axial(const Vec3& p) {
    const Vec3 a = normalize(kP1 - kP0), l = p - kP0;
    const double z = dot(l, a);
    return {length(l - a * z), z};
}

}  // namespace

// dp/du, dp/dv, dn/du, dn/dv against central differences of the shape's own p and n, and the
// default shape operator against a finite difference of n along a tangent.
TEST(GeometryCylinder, DifferentialGeometryMatchesFiniteDifferences) {
    for (bool flip : {false, true}) {
        const Cylinder c(kP0, kP1, kR, flip);
        const double h = 1e-5, tol = 1e-6;
        for (double u : {0.05, 0.3, 0.61, 0.9})
            for (double v : {0.1, 0.45, 0.8}) {
                const SurfaceInteraction si = at(c, u, v);
                EXPECT_NEAR(si.uv.x, u, 1e-12);
                EXPECT_NEAR(si.uv.y, v, 1e-12);
                const SurfaceInteraction up = at(c, u + h, v), um = at(c, u - h, v);
                const SurfaceInteraction vp = at(c, u, v + h), vm = at(c, u, v - h);
                snell::test::expect_differential_geometry(si, up, um, vp, vm, h, tol, tol);
                EXPECT_NEAR(radial_axial(si.p).first, kR, 1e-14);
                // Shape operator along a mixed tangent: n(p + e t) - n(p - e t) over 2e.
                const Vec3 t = normalize(si.dpdu * 0.3 + si.dpdv * 0.8);
                const double e = 1e-6;
                SurfaceInteraction a, b;
                ASSERT_TRUE(c.closest_point(si.p + t * e, 1, &a));
                ASSERT_TRUE(c.closest_point(si.p - t * e, 1, &b));
                EXPECT_LT(length((a.n - b.n) / (2 * e) - c.normal_derivative(si, t)), 1e-6);
            }
    }
}

// Rays from random points towards the cylinder: the hit lies on the mantle within the segment,
// at the nearest such point of the line (checked by marching), and occlusion agrees; rays
// beyond the ends pass through the open cylinder.
TEST(GeometryCylinder, IntersectionIsTheNearestMantlePoint) {
    Scene scene;
    auto c = std::make_shared<Cylinder>(kP0, kP1, kR);
    scene.add_shape(c);
    scene.build();
    PCG32 rng(7, 9);
    int hits = 0;
    for (int i = 0; i < 400; ++i) {
        const Vec3 o = warp::square_to_uniform_sphere(next_2d(rng)) * (0.5 + 3 * rng.next_double()) + kP0;
        const Vec3 target = kP0 + (kP1 - kP0) * rng.next_double() + warp::square_to_uniform_sphere(next_2d(rng)) * 0.8;
        const Vec3 d = normalize(target - o);
        // The first crossing of the mantle by marching the line finely (radial distance = r).
        double t_march = -1;
        const double step = 1e-4;
        for (double t = 1e-3; t < 8; t += step) {
            const auto [r0, z0] = radial_axial(o + d * t);
            const auto [r1, z1] = radial_axial(o + d * (t + step));
            if ((r0 - kR) * (r1 - kR) <= 0 && z0 >= 0 && z0 <= length(kP1 - kP0)) {
                t_march = t;
                break;
            }
        }
        SurfaceInteraction si;
        const bool hit = scene.intersect(Ray{o, d}, &si);
        EXPECT_EQ(hit, t_march > 0) << i;
        EXPECT_EQ(scene.occluded(Ray{o, d}), hit) << i;
        if (!hit || t_march < 0) continue;
        ++hits;
        EXPECT_NEAR(si.t, t_march, 2 * step);
        EXPECT_NEAR(radial_axial(si.p).first, kR, 1e-12);
    }
    EXPECT_GT(hits, 100);
}

// The closest point on the mantle against a dense search over (phi, z); area sampling is uniform
// in (phi, z), so its mean axial coordinate is half the length.
TEST(GeometryCylinder, ClosestPointAndAreaSampling) {
    const Cylinder c(kP0, kP1, kR);
    PCG32 rng(11, 3);
    for (int i = 0; i < 50; ++i) {
        const Vec3 p = kP0 + (kP1 - kP0) * (1.4 * rng.next_double() - 0.2) +
                       warp::square_to_uniform_sphere(next_2d(rng)) * (2 * rng.next_double());
        SurfaceInteraction si;
        ASSERT_TRUE(c.closest_point(p, kInfinity, &si));
        double best = kInfinity;
        for (int a = 0; a < 400; ++a)
            for (int b = 0; b <= 200; ++b) best = std::min(best, length(at(c, a / 400.0, b / 200.0).p - p));
        EXPECT_LE(length(si.p - p), best + 1e-12);
        EXPECT_GT(length(si.p - p), best - 0.02);
    }
    double z = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const ShapeSample s = c.sample_area(next_2d(rng));
        EXPECT_NEAR(radial_axial(s.p).first, kR, 1e-12);
        EXPECT_NEAR(s.pdf, 1 / c.area(), 1e-15);
        z += radial_axial(s.p).second / length(kP1 - kP0);
    }
    EXPECT_NEAR(z / n, 0.5, 0.01);
}
