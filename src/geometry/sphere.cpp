#include "geometry/sphere.h"

#include <stdexcept>

#include "core/warp.h"

namespace snell {

Sphere::Sphere(const Vec3& center, double radius, bool flip_normals)
    : m_center(center), m_radius(radius), m_flip(flip_normals) {
    if (!(radius > 0) || !std::isfinite(radius) || !is_finite(center))
        throw std::runtime_error("sphere: radius must be positive and finite");
}

Bounds3 Sphere::bounds() const {
    // Padded by a relative 1e-5: Embree culls boxes with the float copy of the ray, which
    // deviates from the double ray by float roundoff of origin and direction; the padding
    // keeps grazing hits of the double ray from being culled.
    const double mag = m_radius + max_component(Vec3(std::abs(m_center.x), std::abs(m_center.y), std::abs(m_center.z)));
    const Vec3 r(m_radius + 1e-5 * mag);
    Bounds3 b;
    b.expand(m_center - r);
    b.expand(m_center + r);
    return b;
}

double Sphere::nearest_root(const Ray& ray, double tnear, double tfar) const {
    double t0, t1;
    if (!intersect_line(ray, &t0, &t1)) return -1;
    if (t0 > tnear && t0 < tfar) return t0;
    if (t1 > tnear && t1 < tfar) return t1;  // origin inside the sphere: far side
    return -1;
}

Vec3 Sphere::hit_normal(const Ray& ray, double t) const { return ray.at(t) - m_center; }

bool Sphere::intersect_line(const Ray& ray, double* t0, double* t1) const {
    const Vec3 f = ray.o - m_center;
    const double a = dot(ray.d, ray.d);
    const double b = -dot(f, ray.d);  // half of the usual -b
    const double c = dot(f, f) - m_radius * m_radius;
    // Discriminant as r^2 - |f + (b/a) d|^2 (distance of the line from the centre): no
    // catastrophic cancellation of b^2 - ac for distant origins or tiny spheres.
    const Vec3 l = f + ray.d * (b / a);
    const double disc = a * (m_radius * m_radius - dot(l, l));
    if (disc < 0) return false;
    // Citardauq: the root with the larger magnitude first, the other from Vieta's c/q.
    const double q = b + std::copysign(std::sqrt(disc), b);
    double r0 = c / q, r1 = q / a;
    if (q == 0) r0 = r1 = 0;  // b = disc = 0 forces c = 0: origin on the sphere, tangent ray
    if (r0 > r1) std::swap(r0, r1);
    *t0 = r0;
    *t1 = r1;
    return true;
}

void Sphere::fill_interaction(const Vec3& p, SurfaceInteraction* si) const {
    const Vec3 l = p - m_center;
    const double rxy = std::sqrt(l.x * l.x + l.y * l.y);
    double cos_phi = 1, sin_phi = 0;
    if (rxy > 0) {
        cos_phi = l.x / rxy;
        sin_phi = l.y / rxy;
    }
    si->uv = Vec2(0, 0);
    if (reads_uv()) {
        double phi = std::atan2(l.y, l.x);
        if (phi < 0) phi += 2 * kPi;
        const double theta = std::atan2(rxy, l.z);
        si->uv = {phi * kInv2Pi, theta * kInvPi};
    }

    const double sign = m_flip ? -1.0 : 1.0;
    si->p = p;
    si->t = 0;
    si->dpdu = Vec3(-l.y, l.x, 0) * (2 * kPi);
    si->dpdv = Vec3(l.z * cos_phi, l.z * sin_phi, -rxy) * kPi;
    si->ng = si->n = l * (sign / m_radius);
    si->dndu = si->dpdu * (sign / m_radius);
    si->dndv = si->dpdv * (sign / m_radius);
    si->shading = Frame::from_normal_tangent(si->n, si->dpdu);
    si->shape = this;
    si->prim = 0;
}

void Sphere::compute_interaction(const Ray& ray, double t, uint32_t, const Vec2&, SurfaceInteraction* si) const {
    // Re-project the hit point: its error is then that of one normalisation, independent of t.
    Vec3 l = ray.at(t) - m_center;
    const double len = length(l);
    l = len > 0 ? l * (m_radius / len) : Vec3(0, 0, m_radius);
    fill_interaction(m_center + l, si);
    si->t = t;
    si->wo = -normalize(ray.d);
}

bool Sphere::closest_point(const Vec3& p, double radius, SurfaceInteraction* si) const {
    const Vec3 l = p - m_center;
    const double len = length(l);
    if (std::abs(len - m_radius) > radius) return false;
    // The centre is equidistant from all points; any is a valid answer.
    const Vec3 dir = len > 0 ? l / len : Vec3(0, 0, 1);
    fill_interaction(m_center + dir * m_radius, si);
    si->wo = Vec3();
    return true;
}

ShapeSample Sphere::sample_at(const Vec3& w, double pdf) const {
    SurfaceInteraction si;
    fill_interaction(m_center + w * m_radius, &si);
    ShapeSample s;
    s.p = m_center + w * m_radius;
    s.n = m_flip ? -w : w;
    s.uv = si.uv;
    s.pdf = pdf;
    return s;
}

ShapeSample Sphere::sample_area(const Vec2& u) const {
    const Vec3 w = warp::square_to_uniform_sphere(u);
    return sample_at(w, 1.0 / area());
}

std::optional<ShapeSample> Sphere::sample_from(const Vec3& ref, const Vec2& u) const {
    const Vec3 dc_vec = m_center - ref;
    const double dc2 = length_squared(dc_vec);
    const double r2 = m_radius * m_radius;
    if (dc2 <= r2) return Shape::sample_from(ref, u);

    // Cone of directions towards the sphere (pbrt's approach): sample theta within the cone,
    // then locate the visible point by the angle alpha at the centre instead of intersecting
    // a ray, which stays accurate when the sphere is tiny or far away.
    const double dc = std::sqrt(dc2);
    const double sin2_max = r2 / dc2, sin_max = std::sqrt(sin2_max);
    // 1 - cos(theta_max) without cancellation.
    const double one_minus_cos_max = sin2_max / (1 + safe_sqrt(1 - sin2_max));
    const double one_minus_cos = u.x * one_minus_cos_max;
    const double cos_theta = 1 - one_minus_cos;
    const double sin2_theta = one_minus_cos * (2 - one_minus_cos);
    // Law of sines/cosines in the triangle (ref, centre, point) for the nearer intersection.
    const double cos_alpha = sin2_theta / sin_max + cos_theta * safe_sqrt(1 - sin2_theta / sin2_max);
    const double sin_alpha = safe_sqrt(1 - cos_alpha * cos_alpha);
    const double phi = 2 * kPi * u.y;

    const Frame f = Frame::from_normal(dc_vec / dc);  // n axis points from ref to the centre
    const Vec3 w = f.to_world(Vec3(sin_alpha * std::cos(phi), sin_alpha * std::sin(phi), -cos_alpha));
    return sample_at(w, 1.0 / (2 * kPi * one_minus_cos_max));
}

double Sphere::pdf_from(const Vec3& ref, const Vec3& p, const Vec3& n) const {
    const double dc2 = length_squared(m_center - ref), r2 = m_radius * m_radius;
    if (dc2 <= r2) return Shape::pdf_from(ref, p, n);
    // Cone sampling only produces points on the cap facing ref; elsewhere the density is 0
    // (MNEE asks for it at points reached by refracted paths, which may lie behind the cap).
    if (dot(p - m_center, ref - p) <= 0) return 0.0;
    const double sin2_max = r2 / dc2;
    return 1.0 / (2 * kPi * sin2_max / (1 + safe_sqrt(1 - sin2_max)));
}

Vec3 Sphere::normal_derivative(const SurfaceInteraction& si, const Vec3& tangent) const {
    // n = +-(p - c)/r, so moving p by a tangent vector moves n by the same vector over +-r.
    const Vec3 t = tangent - si.n * dot(si.n, tangent);
    return t * ((m_flip ? -1.0 : 1.0) / m_radius);
}

}  // namespace snell
