#pragma once
// Mitsuba's `roughplastic`: a diffuse base under a rough dielectric coating. The coating
// reflects by a microfacet lobe (Walter et al. 2007, the dielectric Fresnel term); light that
// enters it reaches the base, scatters diffusely and leaves, attenuated by the coating's rough
// transmittance on the way in and out, and boosted by the internal inter-reflections (the
// 1 - R_int denominator). The rough transmittance t(mu) (the transmission lobe's albedo, less
// than 1 - E_spec(mu) by what Smith shadowing loses) and the internal diffuse reflectance are
// tabulated at construction by quadrature of the microfacet lobes, as Mitsuba 3 does.
#include <vector>

#include "bsdf/bsdf.h"
#include "bsdf/microfacet.h"
#include "bsdf/param.h"

namespace snell {

class RoughPlasticBSDF final : public BSDF {
public:
    RoughPlasticBSDF(MicrofacetDistribution distribution, SpectrumParam diffuse_reflectance,
                     SpectrumParam specular_reflectance, double int_ior, double ext_ior, bool nonlinear = false);

    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    uint32_t flags() const override { return kReflection | kGlossy | kDiffuse; }

    /// The coating's rough transmittance seen from outside at cos theta = mu (the albedo of
    /// its transmission lobe, energy not radiance), interpolated from the table.
    double external_transmittance(double mu) const;
    /// Diffuse (cosine-weighted) reflectance of the coating seen from inside.
    double internal_reflectance() const { return m_internal_reflectance; }

private:
    double specular_probability(double t_o) const;

    MicrofacetDistribution m_distr;
    SpectrumParam m_diffuse_reflectance, m_specular_reflectance;
    double m_eta, m_inv_eta2;
    bool m_nonlinear;
    double m_specular_sampling_weight;
    std::vector<double> m_external_transmittance;  ///< over mu in [0, 1], uniform
    double m_internal_reflectance = 0;
};

}  // namespace snell
