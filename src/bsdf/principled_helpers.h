#pragma once
// Pieces the `principled` and `principledthin` BSDFs share (Mitsuba 3's principledhelpers).
#include <algorithm>
#include <cmath>
#include <utility>

#include "core/vector.h"

namespace snell::principled {

/// (1 - cos)^5, Schlick's weight.
inline double schlick_weight(double c) {
    const double m = std::clamp(1.0 - c, 0.0, 1.0);
    return (m * m) * (m * m) * m;
}

/// Schlick's Fresnel with F0 = r0, for the signed cosine cos_i against the microfacet; from the
/// denser side the transmitted angle's weight is used (total internal reflection gives 1).
inline double schlick(double r0, double cos_i, double eta) {
    const double eta_it = cos_i >= 0 ? eta : 1.0 / eta;
    if (eta_it > 1.0) return r0 + (1 - r0) * schlick_weight(std::abs(cos_i));
    const double cos_t2 = 1 - (1 - cos_i * cos_i) / (eta_it * eta_it);
    return r0 + (1 - r0) * schlick_weight(std::sqrt(std::max(0.0, cos_t2)));
}

inline double schlick_r0(double eta) { return sqr((eta - 1) / (eta + 1)); }

/// Both directions on m's side of the macro surface as the reflection (or refraction) needs,
/// with m oriented to wo's side.
inline bool compatible(const Vec3& m_up, const Vec3& wo, const Vec3& wi, bool reflection) {
    const Vec3 m = wo.z >= 0 ? m_up : -m_up;
    return dot(wo, m) > 0 && (reflection ? dot(wi, m) > 0 : dot(wi, m) < 0);
}

/// The shape of the diffuse lobe (times base colour / pi): Burley 2012's retro-reflective
/// diffuse, blended by `flatness` towards Burley 2015's Hanrahan-Krueger "fake subsurface".
/// cos_o and cos_i are the two directions' |cosines|, cos_d their half vector's with one of them.
inline double diffuse_shape(double cos_o, double cos_i, double cos_d, double roughness, double flatness) {
    const double Fo = schlick_weight(cos_i), Fi = schlick_weight(cos_o);
    const double f_diff = (1 - 0.5 * Fi) * (1 - 0.5 * Fo);
    const double Rr = 2 * roughness * cos_d * cos_d;
    const double f_retro = Rr * (Fo + Fi + Fo * Fi * (Rr - 1));
    double shape = f_diff + f_retro;
    if (flatness > 0) {
        const double Fss90 = Rr / 2;
        const double Fss = (1 - Fo + Fss90 * Fo) * (1 - Fi + Fss90 * Fi);
        const double f_ss = 1.25 * (Fss * (1 / (cos_i + cos_o) - 0.5) + 0.5);
        shape = shape * (1 - flatness) + f_ss * flatness;
    }
    return shape;
}

/// Burley 2012: GGX alpha = roughness^2, stretched by aspect = sqrt(1 - 0.9 anisotropic); at
/// least 1e-3 (Mitsuba's calc_dist_params).
inline std::pair<double, double> ggx_alphas(double roughness, double anisotropic) {
    const double r2 = roughness * roughness;
    const double aspect = std::sqrt(1 - 0.9 * anisotropic);
    return {std::max(1e-3, r2 / aspect), std::max(1e-3, r2 * aspect)};
}

}  // namespace snell::principled
