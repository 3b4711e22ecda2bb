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
/// through it to a point light with `reflections` internal reflections between entering and
/// leaving, by exhaustive search in the plane of c, x_b and the light (refraction and reflection
/// about the sphere's normals keep the path in it): a scan of the entry point v1 over the great
/// circle, the ray refracted in, along chords reflected about the normal `reflections` times and
/// out, and bisection on the angle between the leaving ray and the direction to the light. Each
/// path's vertices in order (entry, reflections, exit); vertices and x_b -> v1 above y = 0.
inline std::vector<std::vector<Vec3>> sphere_through_roots(const Vec3& c, double r, double eta, const Vec3& xb,
                                                           const Vec3& light, int reflections, int scan = 200000) {
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
    const auto path = [&](double phi, std::vector<Vec3>* p, double* residual) {
        p->clear();
        const Vec3 n1 = e1 * std::cos(phi) + e2 * std::sin(phi);
        p->push_back(c + n1 * r);
        const Vec3 d0 = normalize(p->back() - xb);
        if (dot(d0, n1) >= 0) return false;
        Vec3 d;
        if (!refract(d0, n1, 1 / eta, &d)) return false;
        for (int k = 0; k <= reflections; ++k) {  // along a chord to the next vertex
            const Vec3 v = p->back() + d * (-2 * dot(d, p->back() - c));
            p->push_back(v);
            if (k < reflections) d = d - normalize(v - c) * (2 * dot(d, normalize(v - c)));
        }
        Vec3 out;
        if (!refract(d, -normalize(p->back() - c), eta, &out)) return false;
        const Vec3 to_light = normalize(light - p->back());
        if (dot(out, to_light) <= 0) return false;
        *residual = dot(cross(out, to_light), e3);
        return true;
    };
    const auto above_ground = [](const std::vector<Vec3>& p) {
        return std::all_of(p.begin(), p.end(), [](const Vec3& v) { return v.y > 0; });
    };
    std::vector<std::vector<Vec3>> roots;
    const double step = 2 * kPi / scan;
    std::vector<Vec3> p;
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
            if (valid && path(0.5 * (lo + hi), &p, &rm) && std::abs(rm) < 1e-9 && above_ground(p)) roots.push_back(p);
        }
        prev = cur;
        prev_ok = ok;
    }
    return roots;
}

/// The paths of sphere_through_roots without internal reflections.
inline std::vector<TwoRefractions> sphere_two_refraction_roots(const Vec3& c, double r, double eta, const Vec3& xb,
                                                               const Vec3& light, int scan = 200000) {
    std::vector<TwoRefractions> out;
    for (const auto& p : sphere_through_roots(c, r, eta, xb, light, 0, scan)) out.push_back({p[0], p[1]});
    return out;
}

}  // namespace snell::test
