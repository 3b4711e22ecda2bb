#pragma once
#include "geometry/analytic_shape.h"

namespace snell {

/// Analytic open cylinder (Mitsuba's `cylinder`: no caps), intersected in double.
///
/// Frame (e1, e2, a) with a the unit axis from p0 to p1 of length L. Parametrisation:
/// p(u, v) = p0 + r (cos ph e1 + sin ph e2) + v L a with ph = 2 pi u, so
/// dp/du = 2 pi r (-sin ph e1 + cos ph e2), dp/dv = L a, n = (cos ph e1 + sin ph e2),
/// dn/du = dp/du / r, dn/dv = 0 (negated when `flip_normals`: n then points to the axis).
class Cylinder final : public AnalyticShape {
public:
    Cylinder(const Vec3& p0, const Vec3& p1, double radius, bool flip_normals = false);

    double nearest_root(const Ray& ray, double tnear, double tfar) const override;
    Vec3 hit_normal(const Ray& ray, double t) const override;
    Bounds3 bounds() const override;
    double area() const override { return 2 * kPi * m_radius * m_length; }
    void compute_interaction(const Ray& ray, double t, uint32_t prim, const Vec2& uv,
                             SurfaceInteraction* si) const override;
    /// Exact: the point on the mantle nearest to p (its axial coordinate clamped to [0, L]).
    bool closest_point(const Vec3& p, double radius, SurfaceInteraction* si) const override;
    ShapeSample sample_area(const Vec2& u) const override;

    /// Fills `si` (t = 0, wo unset) for a point at axial coordinate z in [0, L] and angle phi.
    void fill_interaction(double phi, double z, SurfaceInteraction* si) const;

private:
    Vec3 m_p0, m_axis, m_e1, m_e2;
    double m_length, m_radius;
    bool m_flip;
};

}  // namespace snell
