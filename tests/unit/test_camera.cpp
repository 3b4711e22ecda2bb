// Sensors on their own: the thin lens focuses every lens point of a pixel onto the pinhole's
// point of the focal plane and reduces to the pinhole as the aperture closes; orthographic rays
// are parallel and tile Mitsuba's window.
#include <gtest/gtest.h>

#include <cmath>

#include "camera/orthographic.h"
#include "camera/thinlens.h"

using namespace snell;

namespace {

FilmSpec film(int w, int h) {
    FilmSpec f;
    f.width = w;
    f.height = h;
    return f;
}

const Transform kLook = Transform::look_at(Vec3(1, 2, 3), Vec3(0, 0.5, 0), Vec3(0, 1, 0));

}  // namespace

TEST(ThinLens, EveryLensPointMeetsThePinholeRayOnTheFocalPlane) {
    const PerspectiveCamera pin(kLook, 40, "x", film(64, 48));
    const ThinLensCamera lens(kLook, 40, "x", film(64, 48), 0.3, 2.5);
    EXPECT_TRUE(lens.has_lens());
    EXPECT_EQ(lens.pinhole(), nullptr);
    EXPECT_EQ(pin.pinhole(), &pin);
    const Vec3 axis = pin.forward();
    for (const Vec2 raster : {Vec2(0.5, 0.5), Vec2(32, 24), Vec2(63.9, 10.2)}) {
        const Ray p = pin.generate_ray(raster);
        // The pinhole ray reaches the focal plane (2.5 along the axis) at:
        const Vec3 focus = p.o + p.d * (2.5 / dot(p.d, axis));
        for (const Vec2 u : {Vec2(0.1, 0.2), Vec2(0.9, 0.5), Vec2(0.5, 0.99)}) {
            const Ray r = lens.generate_ray(raster, u);
            EXPECT_NEAR(length(r.d), 1.0, 1e-12);
            // The ray starts on the aperture disk (in the plane through the camera, across the axis)...
            EXPECT_NEAR(dot(r.o - pin.position(), axis), 0.0, 1e-12);
            EXPECT_LE(length(r.o - pin.position()), 0.3 + 1e-12);
            // ... and passes through the focus point.
            const Vec3 q = r.o + r.d * (2.5 / dot(r.d, axis));
            EXPECT_NEAR(length(q - focus), 0.0, 1e-9) << raster.x << "," << raster.y;
            // Clipping stays a distance along the axis.
            EXPECT_NEAR(dot(r.d * r.tmin, axis), 1e-2, 1e-12);
        }
    }
    // A closing aperture gives the pinhole ray.
    const ThinLensCamera tiny(kLook, 40, "x", film(64, 48), 1e-9, 2.5);
    const Ray a = tiny.generate_ray(Vec2(10, 20), Vec2(0.7, 0.3)), b = pin.generate_ray(Vec2(10, 20));
    EXPECT_NEAR(length(a.d - b.d), 0.0, 1e-8);
}

TEST(Orthographic, ParallelRaysOverMitsubasWindow) {
    // Camera space [-1, 1] x [-1/aspect, 1/aspect], scaled by to_world (here by 2 across).
    const Transform to_world = kLook * Transform::scale(Vec3(2, 2, 1));
    const OrthographicCamera cam(to_world, film(40, 20), 0.5, 100);
    EXPECT_FALSE(cam.has_lens());
    EXPECT_EQ(cam.pinhole(), nullptr);
    const Vec3 axis = normalize(kLook.vector(Vec3(0, 0, 1)));
    const Ray c = cam.generate_ray(Vec2(20, 10), Vec2(0.5, 0.5));
    EXPECT_NEAR(length(c.d - axis), 0.0, 1e-12);
    EXPECT_NEAR(length(c.o - (kLook.point(Vec3(0, 0, 0)) + axis * 0.5)), 0.0, 1e-12);  // starts at near_clip
    EXPECT_NEAR(c.tmax, 99.5, 1e-9);
    // The left edge (raster x = 0) is camera +x, scaled by 2; the top edge is +y / aspect.
    const Ray left = cam.generate_ray(Vec2(0, 10), Vec2(0.5, 0.5));
    EXPECT_NEAR(length(left.o - c.o - kLook.vector(Vec3(2, 0, 0))), 0.0, 1e-12);
    const Ray top = cam.generate_ray(Vec2(20, 0), Vec2(0.5, 0.5));
    EXPECT_NEAR(length(top.o - c.o - kLook.vector(Vec3(0, 1, 0))), 0.0, 1e-12);
    EXPECT_NEAR(length(left.d - c.d), 0.0, 1e-15);
}
