#pragma once
// Mitsuba's `conductor`: smooth metal with the exact conductor Fresnel term; one-sided.
#include <optional>

#include "bsdf/bsdf.h"
#include "bsdf/conductor_data.h"
#include "bsdf/param.h"

namespace snell {

class ConductorBSDF final : public BSDF {
public:
    /// `ior`: complex IOR (eta, k) relative to the exterior; std::nullopt is Mitsuba's
    /// material "none", a perfect mirror (F = 1). `specular_reflectance` scales the result.
    explicit ConductorBSDF(std::optional<ConductorIOR> ior,
                           SpectrumParam specular_reflectance = Spectrum::constant(1.0));

    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    uint32_t flags() const override { return kReflection | kSpecular; }

    /// Fresnel reflectance times specular_reflectance at cos(theta) in [0, 1].
    SampledSpectrum reflectance(const BSDFContext& ctx, double cos_theta) const;

private:
    std::optional<ConductorIOR> m_ior;
    SpectrumParam m_specular_reflectance;
};

}  // namespace snell
