#pragma once
// Mitsuba's `diffuse`: ideal Lambertian reflector, one-sided (zero when wo or wi is below).
#include "bsdf/bsdf.h"
#include "bsdf/param.h"

namespace snell {

class DiffuseBSDF final : public BSDF {
public:
    /// `reflectance`: albedo in [0, 1] per wavelength.
    explicit DiffuseBSDF(SpectrumParam reflectance) : m_reflectance(std::move(reflectance)) {}

    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    uint32_t flags() const override { return kReflection | kDiffuse; }
    bool reads_uv() const override { return !m_reflectance.is_constant(); }

    const SpectrumParam& reflectance() const { return m_reflectance; }

private:
    SpectrumParam m_reflectance;
};

}  // namespace snell
