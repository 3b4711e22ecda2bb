#pragma once
#include "core/vector.h"

namespace snell {

/// Orthonormal frame (s, t, n). Local coordinates have n as +z.
struct Frame {
    Vec3 s{1, 0, 0}, t{0, 1, 0}, n{0, 0, 1};

    Frame() = default;
    Frame(const Vec3& s_, const Vec3& t_, const Vec3& n_) : s(s_), t(t_), n(n_) {}

    /// Branchless basis of Duff et al. 2017 ("Building an orthonormal basis, revisited").
    /// Deterministic in n alone, so frames built from the same normal agree from sample to
    /// sample; it is continuous everywhere except across n.z = 0 where the sign flips.
    static Frame from_normal(const Vec3& n) {
        const double sign = std::copysign(1.0, n.z);
        const double a = -1.0 / (sign + n.z);
        const double b = n.x * n.y * a;
        return {Vec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3(b, sign + n.y * n.y * a, -n.y), n};
    }
    /// Frame aligned with a surface tangent: s follows dp/du projected onto the tangent
    /// plane (Gram-Schmidt). Used for shading frames so that tangent frames are smooth over
    /// a surface, which the manifold walk and rough interfaces need (issue #3, point 8).
    static Frame from_normal_tangent(const Vec3& n, const Vec3& dpdu) {
        Vec3 s = dpdu - n * dot(n, dpdu);
        const double l2 = length_squared(s);
        if (!(l2 > 1e-20)) return from_normal(n);
        s /= std::sqrt(l2);
        return {s, cross(n, s), n};
    }

    Vec3 to_local(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
    Vec3 to_world(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

/// Local-frame trigonometry (z is the normal).
inline double cos_theta(const Vec3& w) { return w.z; }
inline double abs_cos_theta(const Vec3& w) { return std::abs(w.z); }
inline double cos2_theta(const Vec3& w) { return w.z * w.z; }
inline double sin2_theta(const Vec3& w) { return std::max(0.0, 1.0 - w.z * w.z); }
inline double tan2_theta(const Vec3& w) { return sin2_theta(w) / cos2_theta(w); }
inline bool same_hemisphere(const Vec3& a, const Vec3& b) { return a.z * b.z > 0; }

}  // namespace snell
