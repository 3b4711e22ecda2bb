#pragma once
// A disk shape local to the light tests, so they do not depend on the geometry module:
// centre c, unit normal n, radius R; area sampling, converted to solid angle in sample_from.
#include "core/frame.h"
#include "core/warp.h"
#include "geometry/shape.h"

namespace snell::test {

class TestDisk final : public Shape {
public:
    TestDisk(const Vec3& c, const Vec3& n, double R) : m_c(c), m_frame(Frame::from_normal(normalize(n))), m_R(R) {}

    unsigned attach(RTCDevice, RTCScene) override { return 0; }
    Bounds3 bounds() const override {
        Bounds3 b;
        b.expand(m_c - Vec3(m_R));
        b.expand(m_c + Vec3(m_R));
        return b;
    }
    double area() const override { return kPi * m_R * m_R; }
    void compute_interaction(const Ray&, double, uint32_t, const Vec2&, SurfaceInteraction*) const override {}
    bool closest_point(const Vec3&, double, SurfaceInteraction*) const override { return false; }

    ShapeSample sample_area(const Vec2& u) const override {
        const Vec2 d = warp::square_to_uniform_disk_concentric(u) * m_R;
        return {m_c + m_frame.to_world(Vec3(d.x, d.y, 0)), m_frame.n, 1.0 / area(), d};
    }
    std::optional<ShapeSample> sample_from(const Vec3& ref, const Vec2& u) const override {
        ShapeSample s = sample_area(u);
        s.pdf = pdf_from(ref, s.p, s.n);
        if (!(s.pdf > 0) || !std::isfinite(s.pdf)) return std::nullopt;
        return s;
    }
    double pdf_from(const Vec3& ref, const Vec3& p, const Vec3& n) const override {
        const Vec3 d = ref - p;
        const double d2 = length_squared(d);
        const double cos = std::abs(dot(n, d)) / std::sqrt(d2);
        return cos > 0 ? d2 / (cos * area()) : 0.0;
    }
    const Vec3& normal() const { return m_frame.n; }

private:
    Vec3 m_c;
    Frame m_frame;
    double m_R;
};

}  // namespace snell::test
