// Instancing (Mitsuba's shapegroup and instance, through Embree instances): a placed shape's hits
// are the group shape's hits carried by the transform (against the same mesh transformed
// directly, and against the exact ray-ellipsoid intersection for a sphere under a non-uniform
// scale), and its differential geometry matches finite differences, mirrored transforms
// included.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "geometry/builders.h"
#include "geometry/instance.h"
#include "geometry/mesh.h"
#include "geometry/sphere.h"
#include "scene/scene.h"
#include "test_geometry_util.h"

using namespace snell;

namespace {

Vec3 sphere_point(double u, double v) {
    const double th = kPi * v, ph = 2 * kPi * u;
    return Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
}

// Non-uniform scale, rotation, translation; and the same mirrored in x.
const Transform kPlace = Transform::translate(Vec3(0.4, -1.2, 2.0)) * Transform::rotate(Vec3(1, 2, 0.5), 37.0) *
                         Transform::scale(Vec3(2.0, 1.0, 0.5));
const Transform kMirror = kPlace * Transform::scale(Vec3(-1, 1, 1));

}  // namespace

TEST(GeometryInstance, DifferentialGeometryCarriedByTheTransform) {
    const Sphere unit(Vec3(0, 0, 0), 1.0);
    for (const Transform& T : {kPlace, kMirror}) {
        const InstancedShape placed(unit, T);
        auto at = [&](double u, double v) {
            SurfaceInteraction si;
            EXPECT_TRUE(unit.closest_point(sphere_point(u, v), kInfinity, &si));
            placed.to_world(&si);
            return si;
        };
        const double h = 1e-5, tol = 2e-5;
        for (double u : {0.1, 0.37, 0.8})
            for (double v : {0.2, 0.55, 0.85}) {
                const SurfaceInteraction si = at(u, v);
                EXPECT_EQ(si.shape, &placed);
                snell::test::expect_differential_geometry(si, at(u + h, v), at(u - h, v), at(u, v + h), at(u, v - h), h,
                                                          tol, tol);
                // Outward: away from the placed centre, for the mirror too.
                EXPECT_GT(dot(si.n, si.p - T.point(Vec3(0, 0, 0))), 0.0);
            }
        // The shape operator along world tangents, at the pole as well (where dp/du vanishes and
        // the (u, v) route cannot invert the metric): against central differences of n.
        for (double v : {0.0, 0.3}) {
            const SurfaceInteraction si = at(0.2, v);
            for (const Vec3 t : {normalize(cross(si.n, Vec3(1, 0, 0))), normalize(cross(si.n, Vec3(0, 1, 0)))}) {
                const double hh = 1e-6;
                SurfaceInteraction a, b;
                ASSERT_TRUE(placed.closest_point(si.p + t * hh, 1.0, &a));
                ASSERT_TRUE(placed.closest_point(si.p - t * hh, 1.0, &b));
                EXPECT_LT(length((a.n - b.n) / (2 * hh) - placed.normal_derivative(si, t)), 1e-4) << "v " << v;
            }
        }
    }
}

TEST(GeometryInstance, HitsMatchDirectGeometryAndTheExactEllipsoid) {
    for (const Transform& T : {kPlace, kMirror}) {
        // The group: a unit sphere and a cube beside it; the direct scene: the cube transformed.
        auto sphere = std::make_shared<Sphere>(Vec3(0, 0, 0), 1.0);
        const Transform cube_at = Transform::translate(Vec3(3, 0, 0)) * Transform::scale(Vec3(0.7, 0.7, 0.7));
        auto cube = std::make_shared<TriangleMesh>(make_cube(cube_at));
        auto group = std::make_shared<ShapeGroup>(std::vector<std::shared_ptr<Shape>>{sphere, cube});
        Scene inst;
        inst.add_instance(std::make_shared<Instance>(group, T));
        inst.build();
        Scene direct;
        direct.add_shape(std::make_shared<TriangleMesh>(make_cube(T * cube_at)));
        direct.build();

        PCG32 rng(3, 5);
        int sphere_hits = 0, cube_hits = 0;
        const Vec3 centre = T.point(Vec3(0, 0, 0)), cube_centre = T.point(Vec3(3, 0, 0));
        for (int k = 0; k < 2000; ++k) {
            const bool aim_cube = k % 2;
            const Vec3 target = (aim_cube ? cube_centre : centre) +
                                Vec3(rng.next_double() - 0.5, rng.next_double() - 0.5, rng.next_double() - 0.5) * 1.5;
            const Vec3 o = target + normalize(Vec3(rng.next_double() - 0.5, rng.next_double() - 0.5, 1.0)) * 10.0;
            const Ray ray{o, normalize(target - o), 0.0, kInfinity};
            SurfaceInteraction si;
            if (!inst.intersect(ray, &si)) continue;
            const auto* placed = dynamic_cast<const InstancedShape*>(si.shape);
            ASSERT_NE(placed, nullptr);
            if (&placed->base() == sphere.get()) {
                // Exact: the ray in the sphere's space meets |o' + t d'| = 1 at the same t.
                const Vec3 lo = T.inverse().point(ray.o), ld = T.inverse().vector(ray.d);
                const double a = dot(ld, ld), b = dot(lo, ld), c = dot(lo, lo) - 1;
                const double t = (-b - std::sqrt(b * b - a * c)) / a;
                EXPECT_NEAR(si.t, t, 1e-9 * t);
                EXPECT_NEAR(length(T.inverse().point(si.p)), 1.0, 1e-9);
                EXPECT_NEAR(length(si.n - normalize(T.normal(T.inverse().point(si.p)))), 0.0, 1e-9);
                ++sphere_hits;
            } else {
                SurfaceInteraction d;
                if (!direct.intersect(ray, &d) || d.t > si.t * (1 + 1e-6)) continue;  // the sphere may shadow
                EXPECT_NEAR(si.t, d.t, 1e-5 * d.t);
                EXPECT_NEAR(length(si.p - d.p), 0.0, 1e-5 * length(d.p));
                EXPECT_NEAR(length(si.ng - d.ng), 0.0, 1e-6);
                ++cube_hits;
            }
            EXPECT_NEAR(length(si.wo + ray.d), 0.0, 1e-12);
            EXPECT_FALSE(inst.occluded(Ray{ray.o, ray.d, 0.0, si.t * (1 - 1e-6)}));
            EXPECT_TRUE(inst.occluded(Ray{ray.o, ray.d, 0.0, si.t * (1 + 1e-6)}));
        }
        EXPECT_GT(sphere_hits, 300);
        EXPECT_GT(cube_hits, 300);
    }
}

TEST(GeometryInstance, ClosestPointAndAreaSamplesStayOnThePlacedSurface) {
    const Sphere unit(Vec3(0, 0, 0), 1.0);
    const InstancedShape placed(unit, kPlace);
    PCG32 rng(9, 1);
    for (int k = 0; k < 200; ++k) {
        const ShapeSample s = placed.sample_area(Vec2(rng.next_double(), rng.next_double()));
        EXPECT_NEAR(length(kPlace.inverse().point(s.p)), 1.0, 1e-9);
        EXPECT_GT(s.pdf, 0.0);
        SurfaceInteraction si;
        ASSERT_TRUE(placed.closest_point(s.p + s.n * 1e-3, 1.0, &si));
        EXPECT_NEAR(length(kPlace.inverse().point(si.p)), 1.0, 1e-9);
        EXPECT_LT(length(si.p - s.p), 5e-3);
    }
}
