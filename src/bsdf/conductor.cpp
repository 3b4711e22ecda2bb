#include "bsdf/conductor.h"

#include "bsdf/fresnel.h"

namespace snell {

ConductorBSDF::ConductorBSDF(std::optional<ConductorIOR> ior, SpectrumParam specular_reflectance)
    : m_ior(std::move(ior)), m_specular_reflectance(std::move(specular_reflectance)) {}

SampledSpectrum ConductorBSDF::eval(const BSDFContext&, const Vec3&, const Vec3&) const { return {}; }
double ConductorBSDF::pdf(const BSDFContext&, const Vec3&, const Vec3&) const { return 0; }

SampledSpectrum ConductorBSDF::reflectance(const BSDFContext& ctx, double cos_theta) const {
    const SampledWavelengths& wl = ctx.wl;
    SampledSpectrum F(1.0);
    if (m_ior)
        for (int i = 0; i < kSpectrumSamples; ++i)
            F[i] = fresnel_conductor(cos_theta, m_ior->eta(wl[i]), m_ior->k(wl[i]));
    return F * m_specular_reflectance.eval(ctx);
}

std::optional<BSDFSample> ConductorBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double, const Vec2&) const {
    if (wo.z <= 0) return std::nullopt;
    BSDFSample s;
    s.wi = reflect(wo);
    s.pdf = 1;
    s.weight = reflectance(ctx, wo.z);
    s.lobe = kReflection | kSpecular;
    return s;
}

}  // namespace snell
