#pragma once
// Mitsuba's `roughconductor`: microfacet metal (Cook-Torrance with Smith shadowing and the
// exact conductor Fresnel term); one-sided.
#include <optional>

#include "bsdf/bsdf.h"
#include "bsdf/conductor_data.h"
#include "bsdf/microfacet.h"
#include "bsdf/param.h"

namespace snell {

class RoughConductorBSDF final : public BSDF {
public:
    /// `ior` as for ConductorBSDF (std::nullopt: F = 1); the distribution carries the
    /// roughness and `sample_visible`.
    RoughConductorBSDF(MicrofacetParam distribution, std::optional<ConductorIOR> ior,
                       SpectrumParam specular_reflectance = Spectrum::constant(1.0));

    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    /// Density of m times the reflection Jacobian 1 / (4 |wi.m|), in solid angle of wi.
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    uint32_t flags() const override { return kReflection | kGlossy; }

    /// The distribution with its constant alphas (textured ones are read per point).
    const MicrofacetDistribution& distribution() const { return m_distr.base(); }

private:
    MicrofacetParam m_distr;
    std::optional<ConductorIOR> m_ior;
    SpectrumParam m_specular_reflectance;
};

}  // namespace snell
