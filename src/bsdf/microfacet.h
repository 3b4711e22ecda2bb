#pragma once
// Microfacet normal distributions (Beckmann, GGX) with the Smith masking-shadowing model,
// following Walter et al. 2007 and Heitz 2014 ("Understanding the masking-shadowing function").
// Conventions: local frame of the macro surface (n = +z); microfacet normals m lie in the
// upper hemisphere; all densities are in solid angle of m.
#include <utility>

#include "core/vector.h"

namespace snell {

class MicrofacetDistribution {
public:
    enum class Type { Beckmann, GGX };

    /// Isotropic distribution with roughness `alpha` (RMS slope for Beckmann).
    MicrofacetDistribution(Type type, double alpha, bool sample_visible = true)
        : MicrofacetDistribution(type, alpha, alpha, sample_visible) {}
    /// Anisotropic distribution: `alpha_u` along the tangent s (x), `alpha_v` along t (y).
    MicrofacetDistribution(Type type, double alpha_u, double alpha_v, bool sample_visible = true);

    Type type() const { return m_type; }
    double alpha_u() const { return m_alpha_u; }
    double alpha_v() const { return m_alpha_v; }
    bool is_isotropic() const { return m_alpha_u == m_alpha_v; }
    /// Mitsuba's `sample_visible`: whether sample()/pdf() use visible normals.
    bool sample_visible() const { return m_sample_visible; }

    /// Normal distribution D(m) (per solid angle of m, per unit macro area); 0 for m.z <= 0.
    /// Normalised so that integral D(m) cos(theta_m) dm = 1.
    double D(const Vec3& m) const;
    /// Smith's auxiliary Lambda(w) of the height-uncorrelated model.
    double lambda(const Vec3& w) const;
    /// Smith masking G1(w, m) = chi+(w.m / w.z) / (1 + Lambda(w)).
    double G1(const Vec3& w, const Vec3& m) const;
    /// Separable Smith shadowing-masking G1(wo, m) G1(wi, m) (Mitsuba's choice).
    double G(const Vec3& wo, const Vec3& wi, const Vec3& m) const;

    /// Samples m from the *global* density D(m) cos(theta_m) (not visible normals): the
    /// manifold walk's rough-interface sampling needs exactly this density (paper Sec. 3.2).
    Vec3 sample_m(const Vec2& u) const;
    /// Solid-angle density of sample_m: D(m) cos(theta_m).
    double pdf_m(const Vec3& m) const;

    /// Samples m from the distribution of normals visible from `wo` (wo.z > 0):
    /// D_wo(m) = G1(wo, m) max(0, wo.m) D(m) / wo.z. Exact for GGX (Heitz 2018); for
    /// Beckmann it falls back to sample_m (and pdf_visible to pdf_m) -- see has_exact_visible().
    Vec3 sample_visible_m(const Vec3& wo, const Vec2& u) const;
    /// Density of sample_visible_m in solid angle of m.
    double pdf_visible_m(const Vec3& wo, const Vec3& m) const;
    /// Whether sample_visible_m draws truly visible normals (GGX) rather than global ones.
    bool has_exact_visible() const { return m_type == Type::GGX; }

    /// Sampling used by the rough BSDFs: visible normals when sample_visible(), else global.
    /// `wo` must have wo.z > 0. Returns (m, density of m in solid angle).
    std::pair<Vec3, double> sample(const Vec3& wo, const Vec2& u) const;
    /// Density of sample().
    double pdf(const Vec3& wo, const Vec3& m) const;

private:
    /// Effective roughness along the azimuth of `w` (projected alpha).
    double projected_alpha(const Vec3& w) const;

    Type m_type;
    double m_alpha_u, m_alpha_v;
    bool m_sample_visible;
};

}  // namespace snell
