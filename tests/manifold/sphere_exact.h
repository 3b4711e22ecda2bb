#pragma once
// Every refracted path from a point inside a smooth glass sphere to a point light outside it, by
// exhaustive search: the refraction vertex lies in the plane of the centre, x_b and the light
// (the normal passes through the centre, and Snell keeps incident, refracted and normal
// directions coplanar), so a scan of the great circle in that plane and bisection on Snell's
// tangential residual find every root. Independent of the manifold walk.
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

}  // namespace snell::test
