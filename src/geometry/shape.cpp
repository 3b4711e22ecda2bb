#include "geometry/shape.h"

namespace snell {

// Default: uniform area sampling, converted to solid angle at `ref` with the Jacobian
// d^2 / |cos theta_p| (pbrt's Shape::Sample(ctx, u) fallback).
std::optional<ShapeSample> Shape::sample_from(const Vec3& ref, const Vec2& u) const {
    ShapeSample s = sample_area(u);
    const Vec3 d = s.p - ref;
    const double d2 = length_squared(d);
    if (!(d2 > 0)) return std::nullopt;
    const double cos_p = abs_dot(s.n, d) / std::sqrt(d2);
    if (!(cos_p > 0)) return std::nullopt;
    s.pdf *= d2 / cos_p;
    if (!std::isfinite(s.pdf)) return std::nullopt;
    return s;
}

double Shape::pdf_from(const Vec3& ref, const Vec3& p, const Vec3& n) const {
    const Vec3 d = p - ref;
    const double d2 = length_squared(d);
    const double cos_p = abs_dot(n, d) / std::sqrt(d2);
    if (!(d2 > 0) || !(cos_p > 0)) return 0;
    return d2 / (cos_p * area());
}

}  // namespace snell
