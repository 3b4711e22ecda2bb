#pragma once
// Mitsuba's `roughdielectric`: rough interface between two dielectrics, the microfacet model
// of Walter et al. 2007 ("Microfacet models for refraction through rough surfaces") with
// separable Smith shadowing. Extensions as for `dielectric`: dispersion and `sigma_a`.
#include <optional>

#include "bsdf/bsdf.h"
#include "bsdf/microfacet.h"
#include "bsdf/param.h"

namespace snell {

class RoughDielectricBSDF final : public BSDF {
public:
    /// `distribution` carries alpha(s) and `sample_visible`; IORs and factors as for
    /// DielectricBSDF.
    RoughDielectricBSDF(MicrofacetParam distribution, Spectrum int_ior, Spectrum ext_ior,
                        SpectrumParam specular_reflectance = Spectrum::constant(1.0),
                        SpectrumParam specular_transmittance = Spectrum::constant(1.0),
                        std::optional<Spectrum> sigma_a = std::nullopt);

    /// f(wo, wi) without cosine; wo and wi on either side. Transmission is scaled by
    /// 1/eta_it^2 in Radiance mode only (eta_it: IOR of wi's side over wo's side).
    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    /// Solid-angle density of sample(): microfacet density times the half-vector Jacobian,
    /// times the Fresnel lobe-selection probability.
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    uint32_t flags() const override { return kReflection | kTransmission | kGlossy; }

    double eta(double lambda) const override { return m_int_ior(lambda) / m_ext_ior(lambda); }
    bool dispersive() const override { return !m_int_ior.is_constant() || !m_ext_ior.is_constant(); }
    bool reads_uv() const override {
        return !m_distr.is_constant() || !m_specular_reflectance.is_constant() ||
               !m_specular_transmittance.is_constant();
    }
    const Spectrum* interior_absorption() const override { return m_sigma_a ? &*m_sigma_a : nullptr; }
    /// The distribution with its constant alphas (textured ones are read per point).
    const MicrofacetDistribution& distribution() const { return m_distr.base(); }
    bool has_microfacet() const override { return true; }
    std::optional<MicrofacetDistribution> microfacet(const BSDFContext& ctx) const override {
        return m_distr.eval(ctx);
    }

private:
    /// Walter et al.'s f(wo, wi) for the relative IOR eta, without the specular_* factors.
    double eval_scalar(const MicrofacetDistribution& distr, double eta, TransportMode mode, const Vec3& wo,
                       const Vec3& wi) const;
    /// Generalised half vector of (wo, wi), oriented to +z; false when degenerate.
    bool half_vector(double eta, const Vec3& wo, const Vec3& wi, Vec3& m) const;

    MicrofacetParam m_distr;
    Spectrum m_int_ior, m_ext_ior;
    SpectrumParam m_specular_reflectance, m_specular_transmittance;
    std::optional<Spectrum> m_sigma_a;
};

}  // namespace snell
