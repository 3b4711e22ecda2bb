#pragma once
#include "geometry/analytic_shape.h"

namespace snell {

/// Analytic sphere (Mitsuba's `sphere`), an Embree user geometry intersected in double.
///
/// Parametrisation (world axes about the centre): p(u, v) = c + r (sin th cos ph,
/// sin th sin ph, cos th) with ph = 2 pi u, th = pi v, so dp/du = 2 pi (-(p-c).y, (p-c).x, 0),
/// dp/dv = pi (..), n = (p-c)/r and dn/du = dp/du / r, dn/dv = dp/dv / r (all negated when
/// `flip_normals`: the normal then points inwards). At the poles dp/du vanishes.
class Sphere final : public AnalyticShape {
public:
    /// `radius` > 0 in world units; `flip_normals` makes n point towards the centre.
    Sphere(const Vec3& center, double radius, bool flip_normals = false);

    double nearest_root(const Ray& ray, double tnear, double tfar) const override;
    Vec3 hit_normal(const Ray& ray, double t) const override;
    Bounds3 bounds() const override;
    BoundingSphere bounding_sphere() const override { return {m_center, m_radius}; }
    double area() const override { return 4 * kPi * m_radius * m_radius; }
    void compute_interaction(const Ray& ray, double t, uint32_t prim, const Vec2& uv,
                             SurfaceInteraction* si) const override;
    /// Exact: the radial projection c + r (p - c)/|p - c|.
    bool closest_point(const Vec3& p, double radius, SurfaceInteraction* si) const override;
    ShapeSample sample_area(const Vec2& u) const override;
    /// Outside: uniform over the cone of directions subtending the sphere (only visible
    /// points are produced); inside: area sampling converted to solid angle.
    std::optional<ShapeSample> sample_from(const Vec3& ref, const Vec2& u) const override;
    double pdf_from(const Vec3& ref, const Vec3& p, const Vec3& n) const override;
    /// Exact shape operator, valid at the poles too: dn = +-(tangent part of `tangent`) / r.
    Vec3 normal_derivative(const SurfaceInteraction& si, const Vec3& tangent) const override;

    const Vec3& center() const { return m_center; }
    double radius() const { return m_radius; }
    bool flip_normals() const { return m_flip; }

    /// Both ray parameters t0 <= t1 where the (double) ray's line meets the sphere; false if
    /// it misses. Uses the cancellation-free discriminant of Haines et al., "Precision
    /// Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7).
    bool intersect_line(const Ray& ray, double* t0, double* t1) const;
    /// Fills `si` (t = 0, wo unset) for a point assumed to lie on the sphere.
    void fill_interaction(const Vec3& p, SurfaceInteraction* si) const;
    /// The sample at unit direction w from the centre, with density pdf.
    ShapeSample sample_at(const Vec3& w, double pdf) const;

private:
    Vec3 m_center;
    double m_radius;
    bool m_flip;
};

}  // namespace snell
