#pragma once
// Sample warps: maps from [0,1)^2 to domains, each with its density (measure in the name).
#include "core/frame.h"
#include "core/vector.h"

namespace snell::warp {

/// Concentric (Shirley-Chiu) map to the unit disk; density 1/pi in area.
inline Vec2 square_to_uniform_disk_concentric(const Vec2& u) {
    const double a = 2 * u.x - 1, b = 2 * u.y - 1;
    if (a == 0 && b == 0) return {0, 0};
    double r, phi;
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = (kPi / 4) * (b / a);
    } else {
        r = b;
        phi = kPi / 2 - (kPi / 4) * (a / b);
    }
    return {r * std::cos(phi), r * std::sin(phi)};
}

/// Cosine-weighted hemisphere around +z; density cos(theta)/pi in solid angle.
inline Vec3 square_to_cosine_hemisphere(const Vec2& u) {
    const Vec2 d = square_to_uniform_disk_concentric(u);
    return {d.x, d.y, safe_sqrt(1 - d.x * d.x - d.y * d.y)};
}
inline double square_to_cosine_hemisphere_pdf(const Vec3& w) { return w.z > 0 ? w.z * kInvPi : 0.0; }

/// Uniform sphere; density 1/(4 pi) in solid angle.
inline Vec3 square_to_uniform_sphere(const Vec2& u) {
    const double z = 1 - 2 * u.x, r = safe_sqrt(1 - z * z), phi = 2 * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline double square_to_uniform_sphere_pdf() { return kInv4Pi; }

/// Uniform hemisphere around +z; density 1/(2 pi) in solid angle.
inline Vec3 square_to_uniform_hemisphere(const Vec2& u) {
    const double z = u.x, r = safe_sqrt(1 - z * z), phi = 2 * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

/// Uniform cone of directions around +z with cos(theta) >= cos_max; density in solid angle
/// 1 / (2 pi (1 - cos_max)).
inline Vec3 square_to_uniform_cone(const Vec2& u, double cos_max) {
    const double z = 1 - u.x * (1 - cos_max), r = safe_sqrt(1 - z * z), phi = 2 * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline double square_to_uniform_cone_pdf(double cos_max) { return 1.0 / (2 * kPi * (1 - cos_max)); }

/// Uniform barycentrics (b0, b1) on a triangle (Heitz 2019 low-distortion map).
inline Vec2 square_to_uniform_triangle(const Vec2& u) {
    double b0, b1;
    if (u.x < u.y) {
        b0 = u.x / 2;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2;
        b0 = u.x - b1;
    }
    return {b0, b1};
}

}  // namespace snell::warp
