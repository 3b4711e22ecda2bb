#include "geometry/cylinder.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace snell {

Cylinder::Cylinder(const Vec3& p0, const Vec3& p1, double radius, bool flip_normals)
    : m_p0(p0), m_length(length(p1 - p0)), m_radius(radius), m_flip(flip_normals) {
    if (!(radius > 0) || !std::isfinite(radius) || !is_finite(p0) || !is_finite(p1) || !(m_length > 0))
        throw std::runtime_error("cylinder: radius must be positive and finite, and p0 != p1");
    m_axis = (p1 - p0) / m_length;
    const Frame f = Frame::from_normal(m_axis);
    m_e1 = f.s;
    m_e2 = f.t;
}

Bounds3 Cylinder::bounds() const {
    // The two rims' boxes, padded (as the sphere's) for the float copy of the ray.
    Bounds3 b;
    const Vec3 p1 = m_p0 + m_axis * m_length;
    const double mag = m_radius + m_length + max_component(Vec3(std::abs(m_p0.x), std::abs(m_p0.y), std::abs(m_p0.z)));
    for (const Vec3& c : {m_p0, p1}) {
        // A rim's extent along world axis i is r sqrt(1 - a_i^2).
        const Vec3 ext(m_radius * std::sqrt(std::max(0.0, 1 - m_axis.x * m_axis.x)),
                       m_radius * std::sqrt(std::max(0.0, 1 - m_axis.y * m_axis.y)),
                       m_radius * std::sqrt(std::max(0.0, 1 - m_axis.z * m_axis.z)));
        b.expand(c - ext - Vec3(1e-5 * mag));
        b.expand(c + ext + Vec3(1e-5 * mag));
    }
    return b;
}

double Cylinder::nearest_root(const Ray& ray, double tnear, double tfar) const {
    // The ray in the cylinder's frame; only the components across the axis enter the quadric.
    const Vec3 f = ray.o - m_p0;
    const double x = dot(f, m_e1), y = dot(f, m_e2), z = dot(f, m_axis);
    const double dx = dot(ray.d, m_e1), dy = dot(ray.d, m_e2), dz = dot(ray.d, m_axis);
    const double a = dx * dx + dy * dy;
    if (!(a > 0)) return -1;  // parallel to the axis
    const double b = -(x * dx + y * dy);
    // Discriminant as r^2 - (distance of the projected line from the axis)^2 (no cancellation).
    const double lx = x + dx * (b / a), ly = y + dy * (b / a);
    const double disc = a * (m_radius * m_radius - (lx * lx + ly * ly));
    if (disc < 0) return -1;
    const double q = b + std::copysign(std::sqrt(disc), b);
    const double c = x * x + y * y - m_radius * m_radius;
    double t0 = q != 0 ? c / q : 0, t1 = q / a;
    if (t0 > t1) std::swap(t0, t1);
    for (const double t : {t0, t1}) {
        const double zt = z + t * dz;
        if (t > tnear && t < tfar && zt >= 0 && zt <= m_length) return t;
    }
    return -1;
}

Vec3 Cylinder::hit_normal(const Ray& ray, double t) const {
    const Vec3 l = ray.at(t) - m_p0;
    return l - m_axis * dot(l, m_axis);
}

void Cylinder::fill_interaction(double phi, double z, SurfaceInteraction* si) const {
    const double c = std::cos(phi), s = std::sin(phi);
    const Vec3 radial = m_e1 * c + m_e2 * s;
    const double sign = m_flip ? -1.0 : 1.0;
    si->p = m_p0 + radial * m_radius + m_axis * z;
    si->t = 0;
    si->uv = {phi * kInv2Pi, z / m_length};
    si->dpdu = (m_e2 * c - m_e1 * s) * (2 * kPi * m_radius);
    si->dpdv = m_axis * m_length;
    si->ng = si->n = radial * sign;
    si->dndu = si->dpdu * (sign / m_radius);
    si->dndv = Vec3();
    si->shading = Frame::from_normal_tangent(si->n, si->dpdu);
    si->shape = this;
    si->prim = 0;
}

void Cylinder::compute_interaction(const Ray& ray, double t, uint32_t, const Vec2&, SurfaceInteraction* si) const {
    // Re-project the hit point onto the mantle (as the sphere does): its error is then that of
    // one normalisation.
    const Vec3 l = ray.at(t) - m_p0;
    double phi = std::atan2(dot(l, m_e2), dot(l, m_e1));
    if (phi < 0) phi += 2 * kPi;
    fill_interaction(phi, std::clamp(dot(l, m_axis), 0.0, m_length), si);
    si->t = t;
    si->wo = -normalize(ray.d);
}

bool Cylinder::closest_point(const Vec3& p, double radius, SurfaceInteraction* si) const {
    const Vec3 l = p - m_p0;
    const double z = std::clamp(dot(l, m_axis), 0.0, m_length);
    const double x = dot(l, m_e1), y = dot(l, m_e2);
    // On the axis every angle is equally near; any is a valid answer.
    double phi = x == 0 && y == 0 ? 0.0 : std::atan2(y, x);
    if (phi < 0) phi += 2 * kPi;
    fill_interaction(phi, z, si);
    si->wo = Vec3();
    return length(si->p - p) <= radius;
}

ShapeSample Cylinder::sample_area(const Vec2& u) const {
    SurfaceInteraction si;
    fill_interaction(2 * kPi * u.x, u.y * m_length, &si);
    ShapeSample s;
    s.p = si.p;
    s.n = si.n;
    s.uv = si.uv;
    s.pdf = 1.0 / area();
    return s;
}

}  // namespace snell
