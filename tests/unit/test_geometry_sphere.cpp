#include <gtest/gtest.h>

#include "bsdf/dielectric.h"
#include "bsdf/diffuse.h"
#include "bsdf/roughdielectric.h"
#include "core/rng.h"
#include "core/warp.h"
#include "geometry/sphere.h"
#include "light/area.h"
#include "scene/scene.h"
#include "test_geometry_util.h"
#include "texture/checkerboard.h"
#include "texture/constant.h"

using namespace snell;
using snell::test::next_2d;

namespace {

Vec3 sphere_point(const Vec3& c, double r, double u, double v) {
    const double th = kPi * v, ph = 2 * kPi * u;
    return c + Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)) * r;
}

SurfaceInteraction at(const Sphere& s, double u, double v) {
    SurfaceInteraction si;
    EXPECT_TRUE(s.closest_point(sphere_point(s.center(), s.radius(), u, v), kInfinity, &si));
    return si;
}

}  // namespace

// dp/du, dp/dv, dn/du, dn/dv against central differences of the shape's own p and n.
TEST(GeometrySphere, DifferentialGeometryMatchesFiniteDifferences) {
    for (bool flip : {false, true}) {
        const Sphere s({0.3, -0.2, 0.5}, 1.7, flip);
        // Central differences: truncation ~ h^2 (2 pi)^3 r / 6 ~ 4e-9, rounding ~ 1e-16 r / h.
        const double h = 1e-5, tol = 1e-6 * s.radius();
        for (double u : {0.05, 0.3, 0.61, 0.9})
            for (double v : {0.1, 0.45, 0.8}) {
                const SurfaceInteraction si = at(s, u, v);
                EXPECT_NEAR(si.uv.x, u, 1e-12);
                EXPECT_NEAR(si.uv.y, v, 1e-12);
                const SurfaceInteraction up = at(s, u + h, v), um = at(s, u - h, v);
                const SurfaceInteraction vp = at(s, u, v + h), vm = at(s, u, v - h);
                snell::test::expect_differential_geometry(si, up, um, vp, vm, h, tol, tol / s.radius());
                const double sign = flip ? -1 : 1;
                EXPECT_NEAR(dot(si.n, normalize(si.p - s.center())), sign, 1e-14);
                EXPECT_NEAR(length(si.shading.n - si.n), 0.0, 1e-14);
            }
    }
}

// Shape operator: matches dn/du, dn/dv through the default (u, v) route away from the poles
// and stays exact at a pole, where dp/du = 0 and the default cannot invert the metric.
TEST(GeometrySphere, NormalDerivativeIncludingPoles) {
    for (bool flip : {false, true}) {
        const Sphere s({0.1, 0.2, -0.3}, 0.7, flip);
        const SurfaceInteraction si = at(s, 0.3, 0.4);
        const Vec3 t = normalize(si.dpdu * 0.3 + si.dpdv * 0.8);
        EXPECT_LT(length(s.normal_derivative(si, t) - s.Shape::normal_derivative(si, t)), 1e-12);
        SurfaceInteraction pole;
        ASSERT_TRUE(s.closest_point(s.center() + Vec3(0, 0, 5), kInfinity, &pole));
        const double h = 1e-6;
        SurfaceInteraction q;
        ASSERT_TRUE(s.closest_point(pole.p + Vec3(h, 0, 0), kInfinity, &q));
        const Vec3 fd = (q.n - pole.n) / h;  // one-sided: the second derivative term is O(h)
        EXPECT_LT(length(s.normal_derivative(pole, Vec3(1, 0, 0)) - fd), 1e-5);
    }
}

TEST(GeometrySphere, ClosestPointIsRadialProjection) {
    const Sphere s({1, 2, 3}, 0.5);
    PCG32 rng(7, 1);
    for (int i = 0; i < 200; ++i) {
        const Vec3 p = s.center() + warp::square_to_uniform_sphere(next_2d(rng)) * (2 * rng.next_double());
        SurfaceInteraction si;
        const double dist = std::abs(length(p - s.center()) - s.radius());
        ASSERT_TRUE(s.closest_point(p, dist * 1.0001 + 1e-12, &si));
        EXPECT_NEAR(length(si.p - s.center()), s.radius(), 1e-14);
        EXPECT_NEAR(length(si.p - p), dist, 1e-13);
        EXPECT_FALSE(s.closest_point(p, dist * 0.999, &si));
    }
}

TEST(GeometrySphere, RayFromInsideHitsFarSide) {
    Scene scene;
    auto s = std::make_shared<Sphere>(Vec3(0.2, 0.1, -0.3), 2.0);
    scene.add_shape(s);
    scene.build();
    PCG32 rng(3, 5);
    for (int i = 0; i < 500; ++i) {
        // Random interior origin: the far-side distance follows from the line equation.
        const Vec3 o = s->center() + warp::square_to_uniform_sphere(next_2d(rng)) * (1.9 * rng.next_double());
        const Vec3 d = warp::square_to_uniform_sphere(next_2d(rng));
        const Vec3 f = o - s->center();
        const double b = dot(f, d), t_exact = -b + std::sqrt(b * b - dot(f, f) + 4.0);
        SurfaceInteraction si;
        ASSERT_TRUE(scene.intersect(Ray{o, d}, &si));
        EXPECT_NEAR(si.t, t_exact, 1e-12);
        EXPECT_NEAR(length(si.p - s->center()), 2.0, 1e-14);
        EXPECT_GT(dot(si.n, d), 0);  // outward normal, seen from inside
        EXPECT_TRUE(scene.occluded(Ray{o, d}));

        // Continue inwards from the hit: the far side is hit again, never the origin spot.
        const Vec3 d2 = -si.n;
        SurfaceInteraction s2;
        ASSERT_TRUE(scene.intersect(scene.spawn_ray(si, d2), &s2));
        EXPECT_NEAR(s2.t, 4.0, 1e-4);
        // Leaving outwards hits nothing.
        EXPECT_FALSE(scene.intersect(scene.spawn_ray(si, si.n), &s2));
    }
}

// Rays passing at impact parameter b close to r, from far away (1e3 radii): the double
// intersection keeps t accurate, and b slightly above r misses.
TEST(GeometrySphere, GrazingRays) {
    Scene scene;
    const double r = 0.25;
    auto s = std::make_shared<Sphere>(Vec3(1, -2, 0.5), r);
    scene.add_shape(s);
    scene.build();
    const double far = 1e3 * r;
    for (double delta : {1e-2, 1e-4, 1e-6, 1e-8}) {
        for (int k = 0; k < 8; ++k) {
            const double ang = 2 * kPi * k / 8;
            const Vec3 side(0, std::cos(ang), std::sin(ang));
            const double b = r * (1 - delta);
            const Ray ray{s->center() - Vec3(far, 0, 0) + side * b, Vec3(1, 0, 0)};
            const double t_exact = far - std::sqrt((r - b) * (r + b));
            SurfaceInteraction si;
            ASSERT_TRUE(scene.intersect(ray, &si)) << delta;
            EXPECT_NEAR(si.t, t_exact, 1e-12 * far);
            EXPECT_NEAR(length(si.p - s->center()), r, 1e-15 * far);
            const Ray miss{s->center() - Vec3(far, 0, 0) + side * (r * (1 + delta)), Vec3(1, 0, 0)};
            EXPECT_FALSE(scene.intersect(miss, &si)) << delta;
            EXPECT_FALSE(scene.occluded(miss)) << delta;
        }
    }
}

TEST(GeometrySphere, AreaSamplingIsUniform) {
    // Archimedes: z is uniform on the sphere, so (z, phi) bins of equal size have equal area.
    const Sphere s({0, 0, 0}, 1.3);
    const int nz = 10, nphi = 20, n = 200000;
    std::vector<double> counts(nz * nphi, 0);
    PCG32 rng(11, 2);
    for (int i = 0; i < n; ++i) {
        const ShapeSample ss = s.sample_area(next_2d(rng));
        ASSERT_NEAR(ss.pdf, 1 / s.area(), 1e-15);
        const Vec3 w = ss.p / s.radius();
        ASSERT_NEAR(length(w), 1.0, 1e-12);
        EXPECT_NEAR(dot(w, ss.n), 1.0, 1e-12);
        double phi = std::atan2(w.y, w.x);
        if (phi < 0) phi += 2 * kPi;
        const int iz = std::min(nz - 1, int((w.z + 1) / 2 * nz));
        const int ip = std::min(nphi - 1, int(phi / (2 * kPi) * nphi));
        counts[iz * nphi + ip] += 1;
    }
    const double chi2 = test::chi2_uniform(counts, double(n) / counts.size());
    EXPECT_GT(test::chi2_upper_tail(chi2, counts.size() - 1), 1e-6) << chi2;
}

// Cone sampling from outside: directions uniform over the cone (chi-square on equal-solid-
// angle bins of (1 - cos theta) and phi), every point visible and the first hit along its
// direction, pdf_from equal to the sampled pdf and to 1 / (2 pi (1 - cos theta_max)).
TEST(GeometrySphere, ConeSamplingFromOutside) {
    auto s = std::make_shared<Sphere>(Vec3(0.5, -0.3, 0.2), 0.8);
    Scene scene;
    scene.add_shape(s);
    scene.build();
    for (double dist : {1.05, 3.0, 400.0}) {
        const Vec3 axis = normalize(Vec3(0.3, 1, -0.4));
        const Vec3 ref = s->center() - axis * (dist * s->radius());
        const double sin2 = 1 / (dist * dist), cos_max = std::sqrt(1 - sin2);
        const double pdf_expected = 1 / (2 * kPi * (1 - cos_max));
        const Frame f = Frame::from_normal(axis);
        const int nb_t = 10, nb_p = 10, n = 100000;
        std::vector<double> counts(nb_t * nb_p, 0);
        PCG32 rng(5, uint64_t(dist * 100));
        for (int i = 0; i < n; ++i) {
            const auto ss = s->sample_from(ref, next_2d(rng));
            ASSERT_TRUE(ss.has_value());
            EXPECT_NEAR(ss->pdf / pdf_expected, 1.0, 1e-9);
            EXPECT_NEAR(s->pdf_from(ref, ss->p, ss->n) / ss->pdf, 1.0, 1e-12);
            EXPECT_NEAR(length(ss->p - s->center()), s->radius(), 1e-12);
            const Vec3 w = normalize(ss->p - ref);
            EXPECT_GE(dot(ss->n, -w), -1e-9);  // on the visible cap
            if (i < 2000 && dist < 100) {
                SurfaceInteraction si;
                ASSERT_TRUE(scene.intersect(Ray{ref, w}, &si));
                EXPECT_NEAR(length(si.p - ss->p), 0.0, 1e-9);
            }
            const Vec3 l = f.to_local(w);
            const double x = (1 - l.z) / (1 - cos_max);
            double phi = std::atan2(l.y, l.x);
            if (phi < 0) phi += 2 * kPi;
            const int it = std::min(nb_t - 1, std::max(0, int(x * nb_t)));
            const int ip = std::min(nb_p - 1, int(phi / (2 * kPi) * nb_p));
            counts[it * nb_p + ip] += 1;
        }
        if (dist < 100) {  // at 400 radii (1 - cos theta) is computed from rounded directions
            const double chi2 = test::chi2_uniform(counts, double(n) / counts.size());
            EXPECT_GT(test::chi2_upper_tail(chi2, counts.size() - 1), 1e-6) << dist << " " << chi2;
        }
    }
}

// Monte Carlo solid angle: uniform directions from ref, fraction hitting the sphere, against
// 2 pi (1 - cos theta_max); the threshold is 5 binomial standard errors.
TEST(GeometrySphere, SolidAngleMatchesCone) {
    auto s = std::make_shared<Sphere>(Vec3(0, 0, 0), 1.0);
    Scene scene;
    scene.add_shape(s);
    scene.build();
    const Vec3 ref(0, 0, 2.5);
    const int n = 200000;
    PCG32 rng(9, 9);
    int hits = 0;
    for (int i = 0; i < n; ++i) hits += scene.occluded(Ray{ref, warp::square_to_uniform_sphere(next_2d(rng))});
    const double p = 1.0 / s->pdf_from(ref, Vec3(0, 0, 1), Vec3(0, 0, 1)) / (4 * kPi);
    const double se = std::sqrt(p * (1 - p) / n);
    EXPECT_NEAR(double(hits) / n, p, 5 * se);
    EXPECT_NEAR(p * 4 * kPi, 2 * kPi * (1 - std::sqrt(1 - 1 / 6.25)), 1e-12);
}

// From inside: E[1/pdf] over sample_from equals the full sphere of directions, 4 pi
// (every direction meets the sphere exactly once); 5 standard errors of the sample mean.
TEST(GeometrySphere, SamplingFromInsideCoversAllDirections) {
    const Sphere s({0, 0, 0}, 1.0);
    const Vec3 ref(0.3, -0.5, 0.2);
    const int n = 200000;
    PCG32 rng(1, 4);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        const auto ss = s.sample_from(ref, next_2d(rng));
        ASSERT_TRUE(ss.has_value());
        EXPECT_NEAR(s.pdf_from(ref, ss->p, ss->n) / ss->pdf, 1.0, 1e-12);
        const double w = 1 / ss->pdf;
        sum += w;
        sum2 += w * w;
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, 4 * kPi, 5 * se);
}

// The uv of a sphere's points costs two atan2 and is read only by textures: Scene::build() lets a
// sphere whose BSDF and emitter read none leave it at (0, 0), every other field as before; a
// textured BSDF or emitter, or no material at all, keeps it.
TEST(GeometrySphere, UvIsFilledWhereItsMaterialReadsIt) {
    Scene scene;
    const auto make = [&](std::shared_ptr<BSDF> bsdf) {
        auto s = std::make_shared<Sphere>(Vec3(0.3, -0.2, 0.5), 1.7);
        if (bsdf) s->set_bsdf(std::move(bsdf));
        scene.add_shape(s);
        return s;
    };
    const auto bare = make(nullptr);
    const auto glass = make(std::make_shared<DielectricBSDF>(Spectrum::constant(1.5), Spectrum::constant(1.0)));
    const auto rough =
        make(std::make_shared<RoughDielectricBSDF>(MicrofacetDistribution(MicrofacetDistribution::Type::Beckmann, 0.1),
                                                   Spectrum::constant(1.5), Spectrum::constant(1.0)));
    const auto white = make(std::make_shared<DiffuseBSDF>(Spectrum::constant(0.5)));
    const TextureRef checks = std::make_shared<CheckerboardTexture>(
        ConstantTexture::make(0.2), ConstantTexture::make(0.8), Transform::scale(Vec3(8, 8, 1)));
    const auto textured = make(std::make_shared<DiffuseBSDF>(SpectrumParam(checks)));
    const auto rough_textured = make(std::make_shared<RoughDielectricBSDF>(
        MicrofacetParam(MicrofacetDistribution(MicrofacetDistribution::Type::Beckmann, 0.1), checks, checks),
        Spectrum::constant(1.5), Spectrum::constant(1.0)));
    // Emitters: an untextured radiance reads no uv, a textured one does.
    const auto lamp = make(nullptr);
    const AreaLight plain(Spectrum::constant(2.0), lamp);
    lamp->set_emitter(&plain);
    const auto lamp_textured = make(std::make_shared<DielectricBSDF>(Spectrum::constant(1.5), Spectrum::constant(1.0)));
    const AreaLight patterned(checks, lamp_textured);
    lamp_textured->set_emitter(&patterned);
    EXPECT_TRUE(glass->reads_uv()) << "true until the scene is built";
    scene.build();
    EXPECT_TRUE(bare->reads_uv());
    EXPECT_FALSE(glass->reads_uv());
    EXPECT_FALSE(rough->reads_uv());
    EXPECT_FALSE(white->reads_uv());
    EXPECT_TRUE(textured->reads_uv());
    EXPECT_TRUE(rough_textured->reads_uv());
    EXPECT_FALSE(lamp->reads_uv());
    EXPECT_TRUE(lamp_textured->reads_uv());

    for (double u : {0.05, 0.61})
        for (double v : {0.1, 0.8}) {
            const SurfaceInteraction full = at(*bare, u, v);
            for (const Sphere* s : {glass.get(), textured.get()}) {
                const SurfaceInteraction si = at(*s, u, v);
                EXPECT_EQ(si.p, full.p);
                EXPECT_EQ(si.n, full.n);
                EXPECT_EQ(si.ng, full.ng);
                EXPECT_EQ(si.dpdu, full.dpdu);
                EXPECT_EQ(si.dpdv, full.dpdv);
                EXPECT_EQ(si.dndu, full.dndu);
                EXPECT_EQ(si.dndv, full.dndv);
                EXPECT_EQ(si.shading.s, full.shading.s);
                EXPECT_EQ(si.shading.t, full.shading.t);
                if (s->reads_uv()) {
                    EXPECT_NEAR(si.uv.x, u, 1e-12);
                    EXPECT_NEAR(si.uv.y, v, 1e-12);
                    EXPECT_EQ(si.uv.x, full.uv.x);
                    EXPECT_EQ(si.uv.y, full.uv.y);
                } else {
                    EXPECT_EQ(si.uv.x, 0.0);
                    EXPECT_EQ(si.uv.y, 0.0);
                }
            }
        }
}
