#pragma once
// Fresnel equations and the mirror/refraction direction helpers shared by all BSDFs.
// Conventions: local shading frame (n = +z); `eta` is always interior over exterior IOR
// (the side n points into is the exterior), so a direction with cos > 0 lies outside.
#include <cmath>

#include "core/vector.h"

namespace snell {

/// Result of the exact dielectric Fresnel equations for unpolarised light.
struct DielectricFresnel {
    double R = 1;       ///< reflectance in [0, 1] (1 under total internal reflection)
    double cos_t = 0;   ///< cosine of the refracted direction; sign opposite to cos_i
    double eta_it = 1;  ///< IOR of the transmitted side over the incident side
    double eta_ti = 1;  ///< 1 / eta_it
};

/// Exact Fresnel reflectance at a smooth dielectric interface. `cos_i` is the signed cosine
/// of the incident direction (pointing away from the surface) with the interface normal;
/// cos_i < 0 means the direction lies inside (eta is inverted then).
inline DielectricFresnel fresnel_dielectric(double cos_i, double eta) {
    DielectricFresnel f;
    const bool outside = cos_i >= 0;
    f.eta_it = outside ? eta : 1.0 / eta;
    f.eta_ti = 1.0 / f.eta_it;
    if (eta == 1.0) {  // index-matched: no interface at all
        f.R = 0;
        f.cos_t = -cos_i;
        return f;
    }
    // Snell's law: sin_t^2 = sin_i^2 / eta_it^2.
    const double cos_i_abs = std::min(std::abs(cos_i), 1.0);
    const double sin2_t = (1 - cos_i_abs * cos_i_abs) * f.eta_ti * f.eta_ti;
    if (sin2_t >= 1) {  // total internal reflection
        f.R = 1;
        f.cos_t = 0;
        return f;
    }
    const double cos_t_abs = std::sqrt(1 - sin2_t);
    // Amplitude coefficients for s and p polarisation.
    const double rs = (cos_i_abs - f.eta_it * cos_t_abs) / (cos_i_abs + f.eta_it * cos_t_abs);
    const double rp = (f.eta_it * cos_i_abs - cos_t_abs) / (f.eta_it * cos_i_abs + cos_t_abs);
    f.R = 0.5 * (rs * rs + rp * rp);
    f.cos_t = outside ? -cos_t_abs : cos_t_abs;
    return f;
}

/// Exact unpolarised Fresnel reflectance of a conductor with complex relative IOR
/// eta + i k (conductor over exterior medium); `cos_i` in [0, 1]. k = 0 reduces to the
/// dielectric case seen from outside.
inline double fresnel_conductor(double cos_i, double eta, double k) {
    // Formulation in terms of a^2 + b^2 = |eta^2 - sin^2 theta| (e.g. Born & Wolf).
    const double c = clamp(cos_i, 0.0, 1.0), c2 = c * c, s2 = 1 - c2;
    const double e2 = eta * eta, k2 = k * k;
    const double t0 = e2 - k2 - s2;
    const double a2pb2 = std::sqrt(std::max(0.0, t0 * t0 + 4 * e2 * k2));
    const double a = safe_sqrt(0.5 * (a2pb2 + t0));
    const double t1 = a2pb2 + c2, t2 = 2 * a * c;
    const double Rs = (t1 - t2) / (t1 + t2);
    const double t3 = c2 * a2pb2 + s2 * s2, t4 = t2 * s2;
    const double Rp = Rs * (t3 - t4) / (t3 + t4);
    return 0.5 * (Rs + Rp);
}

/// Mirror direction about the shading normal (+z).
inline Vec3 reflect(const Vec3& w) { return {-w.x, -w.y, w.z}; }
/// Mirror direction of `w` about the (unit) microfacet normal `m`.
inline Vec3 reflect(const Vec3& w, const Vec3& m) { return m * (2 * dot(w, m)) - w; }
/// Refraction through the shading normal, with `cos_t`/`eta_ti` from fresnel_dielectric.
inline Vec3 refract(const Vec3& w, double cos_t, double eta_ti) { return {-eta_ti * w.x, -eta_ti * w.y, cos_t}; }
/// Refraction of `w` through the microfacet normal `m` (any orientation), with `cos_t`/`eta_ti`
/// from fresnel_dielectric(dot(w, m), eta). The result points away from the surface.
inline Vec3 refract(const Vec3& w, const Vec3& m, double cos_t, double eta_ti) {
    return m * (dot(w, m) * eta_ti + cos_t) - w * eta_ti;
}

/// Hemispherical average of the dielectric Fresnel reflectance for light arriving from the
/// side with IOR ratio `eta` (other side over this side), cosine weighted:
/// 2 * integral_0^1 R(mu) mu dmu. Numerical (Gauss-Legendre on panels), accurate to ~1e-9.
double fresnel_diffuse_reflectance(double eta);

}  // namespace snell
