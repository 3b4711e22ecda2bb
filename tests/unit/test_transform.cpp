#include <gtest/gtest.h>

#include "core/frame.h"
#include "core/transform.h"

using namespace snell;

TEST(Transform, InverseRoundTrip) {
    const Transform t =
        Transform::translate({1, 2, 3}) * Transform::rotate({0.3, 1, -0.2}, 37) * Transform::scale({2, 0.5, 3});
    const Vec3 p(0.3, -1.2, 4.0);
    const Vec3 q = t.inverse().point(t.point(p));
    EXPECT_NEAR(length(q - p), 0.0, 1e-12);
}

TEST(Transform, NormalsStayPerpendicular) {
    const Transform t = Transform::scale({1, 4, 0.5}) * Transform::rotate({1, 1, 0}, 20);
    const Vec3 a(1, 0, 0), b(0, 1, 0), n = cross(a, b);
    EXPECT_NEAR(dot(t.normal(n), t.vector(a)), 0.0, 1e-12);
    EXPECT_NEAR(dot(t.normal(n), t.vector(b)), 0.0, 1e-12);
}

TEST(Transform, LookAtFollowsMitsubaConvention) {
    const Transform t = Transform::look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
    const Vec3 fwd = t.vector({0, 0, 1});
    EXPECT_NEAR(fwd.z, -1.0, 1e-12);
    const Vec3 left = t.vector({1, 0, 0});  // +x is the camera's left
    EXPECT_NEAR(left.x, -1.0, 1e-12);
}

TEST(Frame, OrthonormalForManyNormals) {
    for (int i = 0; i < 1000; ++i) {
        const double th = 0.003 * i, ph = 0.7 * i;
        const Vec3 n(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th) * (i % 2 ? 1 : -1));
        const Frame f = Frame::from_normal(n);
        EXPECT_NEAR(dot(f.s, f.t), 0, 1e-12);
        EXPECT_NEAR(dot(f.s, f.n), 0, 1e-12);
        EXPECT_NEAR(length(f.s), 1, 1e-12);
        EXPECT_NEAR(length(cross(f.s, f.t) - f.n), 0, 1e-12);
    }
}
