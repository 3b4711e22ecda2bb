#pragma once
// Mitsuba's `thindielectric`: a thin slab with two parallel smooth interfaces; inter-reflections
// are summed in closed form and transmission does not bend the ray.
#include "bsdf/bsdf.h"
#include "bsdf/param.h"

namespace snell {

class ThinDielectricBSDF final : public BSDF {
public:
    /// IORs as for DielectricBSDF; transmitted rays leave along -wo.
    ThinDielectricBSDF(Spectrum int_ior, Spectrum ext_ior, SpectrumParam specular_reflectance = Spectrum::constant(1.0),
                       SpectrumParam specular_transmittance = Spectrum::constant(1.0));

    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    uint32_t flags() const override { return kReflection | kTransmission | kSpecular; }
    // eta() stays 1: the slab does not change the direction or the medium of a path.

    /// Total slab reflectance R + T^2 R / (1 - R^2) at |cos_theta| of the incident direction.
    double slab_reflectance(double lambda, double cos_theta) const;
    /// Hero lobe choice, every wavelength weighted by its own slab reflectance.
    SampledSpectrum slab_reflectance(const SampledWavelengths& wl, double cos_theta) const;

private:
    Spectrum m_int_ior, m_ext_ior;
    SpectrumParam m_specular_reflectance, m_specular_transmittance;
};

}  // namespace snell
