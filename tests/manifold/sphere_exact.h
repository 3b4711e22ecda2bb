#pragma once
// Every refracted path from a point inside a smooth glass sphere to a point light outside it, by
// exhaustive search: the refraction vertex lies in the plane of the centre, x_b and the light
// (the normal passes through the centre, and Snell keeps incident, refracted and normal
// directions coplanar), so a scan of the great circle in that plane and bisection on Snell's
// tangential residual find every root. Independent of the manifold walk.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/vector.h"

namespace snell::test {

/// Refraction vertices of the admissible paths x_b -> v -> light through a sphere (centre c,
/// radius r, inside IOR eta > 1) above the plane y = 0, from x_b inside the sphere.
inline std::vector<Vec3> sphere_refraction_roots(const Vec3& c, double r, double eta, const Vec3& xb, const Vec3& light,
                                                 int scan = 200000) {
    // Orthonormal basis of the plane through c, xb and the light.
    const Vec3 e1 = normalize(xb - c);
    Vec3 e2 = (light - c) - e1 * dot(light - c, e1);
    e2 = normalize(e2);
    const auto vertex = [&](double phi) { return c + (e1 * std::cos(phi) + e2 * std::sin(phi)) * r; };
    // Snell's law as a residual: the tangential part of eta wi + wo vanishes.
    const auto residual = [&](double phi) {
        const Vec3 v = vertex(phi), t = e1 * -std::sin(phi) + e2 * std::cos(phi);
        return dot(normalize(xb - v) * eta + normalize(light - v), t);
    };
    std::vector<Vec3> roots;
    const double step = 2 * kPi / scan;
    double prev = residual(0);
    for (int i = 1; i <= scan; ++i) {
        double lo = (i - 1) * step, hi = i * step;
        const double cur = residual(hi);
        if ((prev > 0) != (cur > 0)) {
            const bool lo_pos = prev > 0;
            for (int it = 0; it < 200; ++it) {
                const double mid = 0.5 * (lo + hi);
                ((residual(mid) > 0) == lo_pos ? lo : hi) = mid;
            }
            const Vec3 v = vertex(0.5 * (lo + hi)), n = normalize(v - c);
            const Vec3 wi = normalize(xb - v), wo = normalize(light - v);
            // A refraction (not a sign change of the other branch): wo leaves outwards, x_b is
            // seen from inside, and eta wi + wo points into the sphere; above the ground plane.
            if (dot(wo, n) > 0 && dot(wi, n) < 0 && dot(wi * eta + wo, n) < 0 && v.y > 0) roots.push_back(v);
        }
        prev = cur;
    }
    return roots;
}

/// A path x_b -> v1 -> v2 -> light through a sphere: v1 where it enters, v2 where it leaves.
struct TwoRefractions {
    Vec3 v1, v2;
};

/// Every admissible path from x_b outside a smooth glass sphere (centre c, radius r, IOR eta > 1)
/// through it to a point light, by exhaustive search in the plane of c, x_b and the light (both
/// refractions keep the path in it): a scan of the entry point v1 over the great circle, the ray
/// refracted in, along the chord to v2 and out, and bisection on the angle between the leaving
/// ray and the direction to the light. Vertices and x_b -> v1 above the plane y = 0.
inline std::vector<TwoRefractions> sphere_two_refraction_roots(const Vec3& c, double r, double eta, const Vec3& xb,
                                                               const Vec3& light, int scan = 200000) {
    const Vec3 e1 = normalize(xb - c);
    const Vec3 e2 = normalize((light - c) - e1 * dot(light - c, e1));
    const Vec3 e3 = cross(e1, e2);
    const auto refract = [](const Vec3& d, const Vec3& n, double e, Vec3* out) {  // n faces d's origin
        const double cos_i = -dot(d, n), sin2_t = e * e * (1 - cos_i * cos_i);
        if (sin2_t >= 1) return false;
        *out = normalize(d * e + n * (e * cos_i - std::sqrt(1 - sin2_t)));
        return true;
    };
    // The path from entry angle phi: false where it does not exist (v1 not facing x_b).
    const auto path = [&](double phi, TwoRefractions* p, double* residual) {
        const Vec3 n1 = e1 * std::cos(phi) + e2 * std::sin(phi);
        p->v1 = c + n1 * r;
        const Vec3 d0 = normalize(p->v1 - xb);
        if (dot(d0, n1) >= 0) return false;
        Vec3 d1, d2;
        if (!refract(d0, n1, 1 / eta, &d1)) return false;
        p->v2 = p->v1 + d1 * (-2 * dot(d1, p->v1 - c));
        if (!refract(d1, -normalize(p->v2 - c), eta, &d2)) return false;
        const Vec3 to_light = normalize(light - p->v2);
        if (dot(d2, to_light) <= 0) return false;
        *residual = dot(cross(d2, to_light), e3);
        return true;
    };
    std::vector<TwoRefractions> roots;
    const double step = 2 * kPi / scan;
    TwoRefractions p;
    double prev = 0;
    bool prev_ok = path(0, &p, &prev);
    for (int i = 1; i <= scan; ++i) {
        double lo = (i - 1) * step, hi = i * step, cur = 0;
        const bool ok = path(hi, &p, &cur);
        if (ok && prev_ok && (prev > 0) != (cur > 0)) {
            const bool lo_pos = prev > 0;
            bool valid = true;
            for (int it = 0; it < 200 && valid; ++it) {
                const double mid = 0.5 * (lo + hi);
                double rm = 0;
                valid = path(mid, &p, &rm);
                ((rm > 0) == lo_pos ? lo : hi) = mid;
            }
            double rm = 0;
            if (valid && path(0.5 * (lo + hi), &p, &rm) && std::abs(rm) < 1e-9 && p.v1.y > 0 && p.v2.y > 0)
                roots.push_back(p);
        }
        prev = cur;
        prev_ok = ok;
    }
    return roots;
}

}  // namespace snell::test
